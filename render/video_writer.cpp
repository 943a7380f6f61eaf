#include "render/video_writer.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/errors.hpp"

extern char** environ;

namespace fluidbed::render {
namespace {

// Writes all of `data` to `fd`. SIGPIPE is held on this thread meanwhile, so a dead ffmpeg gives
// EPIPE (an error to report) rather than killing the program; a pending SIGPIPE is consumed.
bool write_all(int fd, const std::uint8_t* data, std::size_t size) {
  sigset_t pipe_set, old;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, &old);
  bool ok = true;
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ok = false;
      break;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  if (!ok) {
    const timespec zero{0, 0};
    sigtimedwait(&pipe_set, nullptr, &zero);
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return ok;
}

// Starts ffmpeg with `args` (args[0] "ffmpeg"), standard input from `in` (or /dev/null when
// in < 0), standard output to /dev/null; posix_spawnp's status (0: started).
// ffmpeg gets a process group of its own: a Ctrl+C at the terminal goes to fluidbed alone, which
// then finishes the video (or its part for a checkpoint) before it stops.
int spawn_ffmpeg(std::vector<std::string> args, int in, pid_t* pid) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (in >= 0)
    posix_spawn_file_actions_adddup2(&actions, in, 0);
  else
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  const int rc = posix_spawnp(pid, "ffmpeg", &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  return rc;
}

}  // namespace

void join_videos(const std::vector<std::string>& parts, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (parts.size() == 1) {  // a second name for it (a copy where a link cannot be made)
    const std::string partial = path + ".part";
    fs::remove(partial, ec);
    fs::create_hard_link(parts[0], partial, ec);
    if (ec) fs::copy_file(parts[0], partial, fs::copy_options::overwrite_existing, ec);
    if (!ec) fs::rename(partial, path, ec);
    if (ec) throw std::runtime_error("video: cannot write " + path + ": " + ec.message());
    return;
  }
  const std::string list = path + ".parts.txt", partial = path + ".part";
  {
    std::FILE* f = std::fopen(list.c_str(), "w");
    if (!f) throw std::runtime_error("video: cannot write " + list);
    for (const std::string& p : parts) {  // quoted; a quote inside as '\''
      std::string quoted;
      for (const char c : fs::absolute(p).string()) {
        if (c == '\'')
          quoted += "'\\''";
        else
          quoted += c;
      }
      std::fprintf(f, "file '%s'\n", quoted.c_str());
    }
    if (std::fclose(f) != 0) throw std::runtime_error("video: cannot write " + list);
  }
  pid_t pid = -1;
  const int rc = spawn_ffmpeg({"ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y",
                               "-f", "concat", "-safe", "0", "-i", list, "-c", "copy", "-movflags",
                               "+faststart", "-f", "mp4", partial},
                              -1, &pid);
  if (rc != 0)
    throw std::runtime_error(std::string("video: cannot start ffmpeg (") + std::strerror(rc) +
                             "); install Debian's ffmpeg");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  fs::remove(list, ec);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    fs::remove(partial, ec);
    throw std::runtime_error("video: ffmpeg failed joining the parts of " + path);
  }
  fs::rename(partial, path, ec);
  if (ec) throw std::runtime_error("video: cannot move " + partial + " into place: " + ec.message());
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), partial_(path + ".part"), width_(width), height_(height) {
  if (width % 2 != 0 || height % 2 != 0)
    throw InputError("video frames need an even width and height, got " + std::to_string(width) +
                     "x" + std::to_string(height));
  if (!(fps > 0.0)) throw InputError("video frame rate must be positive");
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("video: cannot make a pipe to ffmpeg");
  char size[32], rate[32];
  std::snprintf(size, sizeof size, "%dx%d", width, height);
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args = {"ffmpeg", "-nostdin", "-hide_banner", "-loglevel", "error", "-y",
                                   "-f", "rawvideo", "-pix_fmt", "rgb24", "-video_size", size,
                                   "-framerate", rate, "-i", "pipe:0", "-an", "-c:v", "libx264",
                                   "-preset", "veryfast", "-crf", "20", "-pix_fmt", "yuv420p",
                                   "-movflags", "+faststart", "-f", "mp4", partial_};
  // -nostdin only stops ffmpeg reading keys from the terminal; the frames come as input pipe:0.
  pid_t pid = -1;
  const int rc = spawn_ffmpeg(args, fds[0], &pid);
  ::close(fds[0]);
  if (rc != 0) {
    ::close(fds[1]);
    throw std::runtime_error(std::string("video: cannot start ffmpeg (") + std::strerror(rc) +
                             "); install Debian's ffmpeg");
  }
  fd_ = fds[1];
  pid_ = pid;
}

VideoWriter::~VideoWriter() {
  if (pid_ < 0) return;
  ::close(fd_);
  kill(pid_, SIGTERM);
  int status = 0;
  waitpid(pid_, &status, 0);
  std::error_code ec;
  std::filesystem::remove(partial_, ec);
}

void VideoWriter::write(const Image& frame) {
  if (pid_ < 0) throw std::runtime_error("video: already closed");
  if (frame.width != width_ || frame.height != height_)
    throw std::invalid_argument("video: frame size differs from the video's");
  if (!write_all(fd_, frame.rgb.data(), frame.rgb.size()))
    throw std::runtime_error("video: ffmpeg stopped taking frames (see its message above)");
  ++frames_;
}

void VideoWriter::close() {
  if (pid_ < 0) return;
  ::close(fd_);
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("video: ffmpeg failed writing " + path_);
  std::error_code ec;
  std::filesystem::rename(partial_, path_, ec);
  if (ec) throw std::runtime_error("video: cannot move " + partial_ + " into place: " + ec.message());
}

}  // namespace fluidbed::render

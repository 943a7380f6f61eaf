#include "io/vtk_writer.hpp"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/text_format.hpp"

namespace fluidbed {
namespace {

static_assert(std::endian::native == std::endian::little, "the files say LittleEndian");

constexpr char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

void base64(const std::vector<std::uint8_t>& in, std::string& out) {
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t{in[i]} << 16) | (std::uint32_t{in[i + 1]} << 8) | in[i + 2];
    out += kBase64[(v >> 18) & 63];
    out += kBase64[(v >> 12) & 63];
    out += kBase64[(v >> 6) & 63];
    out += kBase64[v & 63];
  }
  if (i < in.size()) {
    const bool two = i + 1 < in.size();
    const std::uint32_t v = (std::uint32_t{in[i]} << 16) | (two ? std::uint32_t{in[i + 1]} << 8 : 0u);
    out += kBase64[(v >> 18) & 63];
    out += kBase64[(v >> 12) & 63];
    out += two ? kBase64[(v >> 6) & 63] : '=';
    out += '=';
  }
}

// One <DataArray> of `components` values per tuple, from `values` (any arithmetic type, converted
// to T), as base64 of (UInt32 byte count, values).
template <class T, class V>
void data_array(std::ostream& o, const char* vtk_type, const std::string& name, int components,
                const std::vector<V>& values, const char* indent) {
  const auto bytes = static_cast<std::uint32_t>(values.size() * sizeof(T));
  std::vector<std::uint8_t> raw(sizeof bytes + bytes);
  std::memcpy(raw.data(), &bytes, sizeof bytes);
  for (std::size_t k = 0; k < values.size(); ++k) {
    const T t = static_cast<T>(values[k]);
    std::memcpy(raw.data() + sizeof bytes + k * sizeof(T), &t, sizeof(T));
  }
  std::string text;
  base64(raw, text);
  o << indent << "<DataArray type=\"" << vtk_type << "\"";
  if (!name.empty()) o << " Name=\"" << name << "\"";
  o << " NumberOfComponents=\"" << components << "\" format=\"binary\">" << text
    << "</DataArray>\n";
}

void floats(std::ostream& o, const std::string& name, int components, const std::vector<double>& v,
            const char* indent) {
  data_array<float>(o, "Float32", name, components, v, indent);
}

// (a, b, c) per tuple from up to three arrays (an empty one gives zeros).
std::vector<double> interleave(std::size_t n, const std::vector<double>& a,
                               const std::vector<double>& b, const std::vector<double>& c,
                               double c_constant = 0.0) {
  std::vector<double> out(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    out[3 * i] = i < a.size() ? a[i] : 0.0;
    out[3 * i + 1] = i < b.size() ? b[i] : 0.0;
    out[3 * i + 2] = i < c.size() ? c[i] : c_constant;
  }
  return out;
}

void time_field(std::ostream& o, double t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", t);
  o << "    <FieldData>\n"
    << "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">"
    << buf << "</DataArray>\n"
    << "    </FieldData>\n";
}

std::string number(double v) { return format_number("%.17g", v); }

}  // namespace

void write_particles_vtp(const std::string& path, const Snapshot& s) {
  const std::size_t n = s.particles();
  const std::vector<double> none;
  std::vector<double> ids(n), offsets(n), mid(n, 0.5 * s.thickness);
  for (std::size_t i = 0; i < n; ++i) {
    ids[i] = static_cast<double>(i);
    offsets[i] = static_cast<double>(i + 1);
  }
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt32\">\n"
    << "  <PolyData>\n";
  time_field(o, s.time);
  o << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfVerts=\"" << n
    << "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
    << "      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  const char* in = "        ";
  // A monolayer's z components are 0 (its arrays across the slab are empty); a thick bed's are
  // its own.
  floats(o, "velocity", 3, interleave(n, s.vx, s.vy, s.vz), in);
  floats(o, "force", 3, interleave(n, s.fx, s.fy, s.fz), in);
  floats(o, "torque", 3, interleave(n, s.torque_x, s.torque_y, s.torque), in);
  floats(o, "spin", 3, interleave(n, s.spin_x, s.spin_y, s.spin), in);
  floats(o, "overlap", 1, s.overlap.size() == n ? s.overlap : std::vector<double>(n, 0.0), in);
  floats(o, "radius", 1, s.radius, in);
  floats(o, "initial_height", 1, s.initial_y.size() == n ? s.initial_y : s.y, in);
  data_array<std::int32_t>(o, "Int32", "id", 1, ids, in);
  o << "      </PointData>\n"
    << "      <Points>\n";
  // A monolayer's centres are on the slab's mid-plane; a thick bed's where its z puts them.
  floats(o, "", 3, interleave(n, s.x, s.y, s.z.size() == n ? s.z : mid), in);
  o << "      </Points>\n"
    << "      <Verts>\n";
  data_array<std::int32_t>(o, "Int32", "connectivity", 1, ids, in);
  data_array<std::int32_t>(o, "Int32", "offsets", 1, offsets, in);
  o << "      </Verts>\n"
    << "    </Piece>\n"
    << "  </PolyData>\n"
    << "</VTKFile>\n";
  write_file_atomically(path, [&](std::ostream& out) { out << o.str(); });
}

namespace {

// An ImageData file of nx x ny cells of dx x dy (x the slab's thickness) from (0, y0) at the
// snapshot's time:
// `cell_data` writes the cells' arrays (`scalars`, `vectors`: the attributes ParaView shows first).
template <class CellData>
void write_image_vti(const std::string& path, const Snapshot& s, int nx, int ny, double dx,
                     double dy, double y0, const char* attributes, CellData cell_data) {
  const std::string extent = "0 " + std::to_string(nx) + " 0 " + std::to_string(ny) + " 0 1";
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt32\">\n"
    << "  <ImageData WholeExtent=\"" << extent << "\" Origin=\"0 " << number(y0) << " 0\" Spacing=\""
    << number(dx) << " " << number(dy) << " " << number(s.thickness) << "\">\n";
  time_field(o, s.time);
  o << "    <Piece Extent=\"" << extent << "\">\n"
    << "      <CellData " << attributes << ">\n";
  cell_data(o, "        ");
  o << "      </CellData>\n"
    << "    </Piece>\n"
    << "  </ImageData>\n"
    << "</VTKFile>\n";
  write_file_atomically(path, [&](std::ostream& out) { out << o.str(); });
}

}  // namespace

void write_gas_vti(const std::string& path, const Snapshot& s) {
  if (!s.has_gas()) return;
  const auto cells = static_cast<std::size_t>(s.nx) * static_cast<std::size_t>(s.ny);
  write_image_vti(path, s, s.nx, s.ny, s.width / s.nx, s.gas_dy(), s.gas_bottom,
                  "Scalars=\"porosity\" Vectors=\"velocity\"",
                  [&](std::ostringstream& o, const char* in) {
                    const std::vector<double> none;
                    floats(o, "velocity", 3, interleave(cells, s.gas_ux, s.gas_uy, none), in);
                    floats(o, "porosity", 1, s.porosity, in);
                    floats(o, "pressure", 1, s.pressure, in);
                  });
}

void write_void_vti(const std::string& path, const Snapshot& s) {
  if (s.void_fraction.empty()) return;
  write_image_vti(path, s, s.void_nx, s.void_ny, s.void_dx, s.void_dy, 0.0,
                  "Scalars=\"void_fraction\"", [&](std::ostringstream& o, const char* in) {
                    const std::vector<double> eps(s.void_fraction.begin(), s.void_fraction.end());
                    floats(o, "void_fraction", 1, eps, in);
                  });
}

VtkSeries::VtkSeries(std::string dir, Written before)
    : dir_(std::move(dir)),
      times_(std::move(before.times)),
      gas_(before.gas),
      void_(before.void_fraction) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw InputError("cannot create the VTK folder " + dir_ + ": " + ec.message());
}

void VtkSeries::write(const Snapshot& s) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu", times_.size());
  const std::filesystem::path d(dir_);
  write_particles_vtp((d / ("particles_" + std::string(name) + ".vtp")).string(), s);
  gas_ = gas_ || s.has_gas();
  if (s.has_gas()) write_gas_vti((d / ("gas_" + std::string(name) + ".vti")).string(), s);
  void_ = void_ || !s.void_fraction.empty();
  if (!s.void_fraction.empty())
    write_void_vti((d / ("void_" + std::string(name) + ".vti")).string(), s);
  times_.push_back(s.time);
  write_collection("particles", "vtp");
  if (gas_) write_collection("gas", "vti");
  if (void_) write_collection("void", "vti");
}

void VtkSeries::write_collection(const std::string& name, const std::string& ext) const {
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "  <Collection>\n";
  for (std::size_t k = 0; k < times_.size(); ++k) {
    char file[64];
    std::snprintf(file, sizeof file, "%s_%06zu.%s", name.c_str(), k, ext.c_str());
    o << "    <DataSet timestep=\"" << number(times_[k]) << "\" group=\"\" part=\"0\" file=\""
      << file << "\"/>\n";
  }
  o << "  </Collection>\n"
    << "</VTKFile>\n";
  write_file_atomically((std::filesystem::path(dir_) / (name + ".pvd")).string(),
                        [&](std::ostream& out) { out << o.str(); });
}

}  // namespace fluidbed

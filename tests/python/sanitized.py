"""The module's tests under AddressSanitizer and UBSan (a sanitizer build with -DFLUIDBED_PYTHON=ON:
tests/CMakeLists.txt runs this instead of pytest alone).

python3 is not built with ASan, so its runtime and the C++ library it intercepts are loaded first
into the interpreter that runs the tests (LD_PRELOAD, from FLUIDBED_PRELOAD that ctest sets; not
into this one). At the interpreter's exit LeakSanitizer reports what the interpreter,
NumPy and Mesa still hold; those are theirs. A leak is ours when a frame of its stack is in
fluidbed's module (_core) or our sources: this fails on those alone, and on any other error the
sanitizers report (they end the process with their own status).
"""

import os
import re
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
OURS = re.compile(r"_core\.cpython|" + re.escape(str(SOURCE)) + r"/(app|engine|render)/")


def main():
    env = dict(os.environ)
    env["LD_PRELOAD"] = os.environ["FLUIDBED_PRELOAD"]
    # Leaks reported, not fatal: this script decides which are ours.
    env["LSAN_OPTIONS"] = "exitcode=0"
    p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                        *sys.argv[1:]], env=env, stderr=subprocess.PIPE, text=True)
    sys.stderr.write(p.stderr)
    blocks = re.split(r"\n(?=(?:Direct|Indirect) leak of )", p.stderr)
    ours = [b for b in blocks if re.match(r"(Direct|Indirect) leak of ", b) and OURS.search(b)]
    others = sum(1 for b in blocks if re.match(r"(Direct|Indirect) leak of ", b)) - len(ours)
    print(f"sanitized: pytest exited {p.returncode}; {len(ours)} leaks of ours, {others} of the "
          "interpreter and the libraries it loaded (not ours)")
    for b in ours:
        print(b.split("\n\n")[0])
    return 1 if p.returncode != 0 or ours else 0


if __name__ == "__main__":
    sys.exit(main())

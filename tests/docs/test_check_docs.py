#!/usr/bin/env python3
"""The documentation test finds what it is for: check_docs.py over fixtures/faults.md, a page with
one fault of each kind, must fail and name every fault, and pass the page's good blocks.

Usage: test_check_docs.py --program PATH --source DIR --work DIR
"""
import argparse
import os
import subprocess
import sys

EXPECTED = [
    "fluidbed run has no option --untill",
    "fluidbed has no verb 'simulate'",
    "names assets/scenes/no_such_scene.toml, which does not exist",
    "no lesson 'no-such-lesson'",
    "no study 'no-such-study'",
    "exit 2, expected 0",
    "exit 0, expected 2",
    "the link no-such-page.md leads nowhere",
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--program", required=True)
    ap.add_argument("--source", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    r = subprocess.run([sys.executable, os.path.join(here, "check_docs.py"), "--program", a.program,
                        "--source", a.source, "--work", a.work,
                        "--page", "tests/docs/fixtures/faults.md"], capture_output=True, text=True)
    out = r.stdout + r.stderr
    missing = [e for e in EXPECTED if e not in out]
    fails = [line for line in out.split("\n") if line.startswith("FAIL ")]
    ok = r.returncode == 1 and not missing and len(fails) == len(EXPECTED)
    # The good block (a shortened run with a file from its marker) ran and passed.
    ok = ok and "faults.md:43: exit 0" in out
    if not ok:
        print(out)
        print(f"exit {r.returncode} (expected 1); not found: {missing}; {len(fails)} failures "
              f"reported, {len(EXPECTED)} expected")
        return 1
    print(f"check_docs.py found all {len(EXPECTED)} faults of the fixture and passed its good block")
    return 0


if __name__ == "__main__":
    sys.exit(main())

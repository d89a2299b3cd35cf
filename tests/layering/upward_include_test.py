#!/usr/bin/python3
"""scripts/check-layering catches what it is for: on a copy of src/ and apps/
with an upward include (core -> setup), a toml++ include in analysis/ and a
std::ofstream in engine/, it exits 1 and names each of the three, and
nothing else (a std::ofstream in a comment is no violation).

Usage: upward_include_test.py REPO_ROOT
"""
import os
import shutil
import subprocess
import sys
import tempfile


def check(script, root):
    r = subprocess.run([sys.executable, script, "--root", root], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def insert_line(path, number, line):
    """Puts line at 1-based line number of path."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    lines.insert(number - 1, line)
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


def main():
    repo = os.path.abspath(sys.argv[1])
    script = os.path.join(repo, "scripts", "check-layering")
    failures = []
    with tempfile.TemporaryDirectory(prefix="orodem-layering-") as tmp:
        for top in ("src", "apps"):
            shutil.copytree(os.path.join(repo, top), os.path.join(tmp, top))

        rc, out = check(script, tmp)
        if rc != 0:
            print(f"the unchanged copy does not pass (exit {rc}):\n{out}")
            return 1

        insert_line(os.path.join(tmp, "src/orodem/core/error.hpp"), 1, '#include "orodem/setup/wedge.hpp"')
        insert_line(os.path.join(tmp, "src/orodem/analysis/wedge_profile.cpp"), 2, "#include <toml++/toml.h>")
        insert_line(os.path.join(tmp, "src/orodem/engine/simulation.cpp"), 3,
                    'namespace orodem { inline void dump() { std::ofstream out("state.txt"); } }')
        insert_line(os.path.join(tmp, "src/orodem/engine/health.cpp"), 1,
                    "// A comment naming std::ofstream and toml::parse is no violation.")

        rc, out = check(script, tmp)
        print(out, end="")
        if rc != 1:
            failures.append(f"exit status {rc}, not 1")
        expected = [
            ("src/orodem/core/error.hpp:1:", "orodem/setup/wedge.hpp", "rule a"),
            ("src/orodem/analysis/wedge_profile.cpp:2:", "toml++/toml.h", "rule b"),
            ("src/orodem/engine/simulation.cpp:3:", "std::ofstream", "rule c"),
        ]
        lines = out.splitlines()
        for where, what, rule in expected:
            if not any(l.startswith(where) and what in l and rule in l for l in lines):
                failures.append(f"no line '{where} ... {what} ... [{rule} ...]'")
        reported = [l for l in lines if not l.startswith("layering:")]
        if len(reported) != len(expected):
            failures.append(f"{len(reported)} violations reported, expected {len(expected)}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

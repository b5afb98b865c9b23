#!/usr/bin/env python3
"""Run the examples of the documentation as a reader would paste them, and check what they print.

Usage: python3 docs/examples.py [--bin DIR] [--python PY] [--keep] [FILE.md ...]

Default files: README.md, the guides docs/*.md and crates/meshbool-py/README.md (js/README.md
is checked by the JavaScript package's own test, js/test/readme.test.mjs).

What runs, per file, in order, in one fresh scratch directory (with `docs/` of this checkout
linked into it, so `python3 docs/render.py` works as it does from a clone):

- ```console blocks: each `$ COMMAND` line (a trailing backslash continues it) runs in bash
  with `meshbool` found on PATH (`--bin`, default target/release) and `python3` the
  interpreter of `--python`. The lines after it, up
  to the next `$`, are what it prints (standard output and error together, as a terminal
  shows them): each must match a line of the output, in the order given (lines left out
  of the example are allowed), where `…` stands for any text and trailing spaces do not
  count. A line `(exit N)` says the command ends with status N; any other command must
  succeed.
- ```python blocks (in files whose name contains "python", in docs/cluster.md, and in the
  Python README):
  joined into one script and run by `--python` (default: .venv/bin/python when it exists,
  else python3) in the scratch directory; they check themselves with `assert`.

`--keep` leaves the scratch directories (and what the examples wrote, the README's pictures
among them) in place and prints where they are.

Other blocks (```sh set-up commands, ```text, ```rust: doctests run by cargo) are not run.
Exits 1 naming the file, line, command and the first expected line that was not printed.
"""
import argparse
import contextlib
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
EXIT = re.compile(r"^\(exit (\d+)\)$")
TIMEOUT = 600  # seconds a command or a file's Python examples may take


def blocks(text):
    """Yield (info, first line number, lines) for every fenced block of a Markdown text."""
    info, start, body = None, 0, []
    for number, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if info is None:
            if stripped.startswith("```"):
                info, start, body = stripped[3:].strip(), number + 1, []
        elif stripped.startswith("```"):
            yield info, start, body
            info = None
        else:
            body.append(line)


def commands(start, lines):
    """The `$ ` commands of a console block: (line number, command, expected lines)."""
    out = []
    i = 0
    while i < len(lines):
        line = lines[i]
        if not line.startswith("$ "):
            i += 1
            continue
        number, command = start + i, line[2:]
        while command.endswith("\\") and i + 1 < len(lines):
            i += 1
            command = command[:-1] + "\n" + lines[i]
        i += 1
        expected = []
        while i < len(lines) and not lines[i].startswith("$ "):
            if lines[i].strip():
                expected.append(lines[i].rstrip())
            i += 1
        out.append((number, command, expected))
    return out


def pattern(line):
    """A regular expression for one expected line: `…` is any text."""
    return re.compile("^" + ".*".join(re.escape(part) for part in line.split("…")) + r"\s*$")


def check_output(expected, printed):
    """The first expected line that the printed lines do not show in order, or None."""
    actual = [line.rstrip() for line in printed.splitlines()]
    at = 0
    for line in expected:
        regex = pattern(line)
        while at < len(actual) and not regex.match(actual[at]):
            at += 1
        if at == len(actual):
            return line
        at += 1
    return None


def run(argv, scratch, env):
    """Runs `argv` in `scratch`: its exit status (None when it ran past TIMEOUT seconds)
    and what it printed, standard output and error together."""
    try:
        done = subprocess.run(
            argv,
            cwd=scratch,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=TIMEOUT,
        )
    except subprocess.TimeoutExpired as late:
        # What it printed comes as bytes here, whatever `text` says.
        return None, (late.output or b"").decode(errors="replace")
    return done.returncode, done.stdout


def run_console(path, start, lines, scratch, env, failures):
    for number, command, expected in commands(start, lines):
        status = 0
        if expected and EXIT.match(expected[-1]):
            status = int(EXIT.match(expected.pop()).group(1))
        code, printed = run(["bash", "-o", "pipefail", "-c", command], scratch, env)
        if code is None:
            failures.append(f"{path}:{number}: `{command}` ran past {TIMEOUT} s")
            return False
        if code != status:
            failures.append(f"{path}:{number}: `{command}` exited {code}, not {status}\n{printed}")
            return False
        missing = check_output(expected, printed)
        if missing is not None:
            failures.append(
                f"{path}:{number}: `{command}` did not print\n    {missing}\n"
                f"  it printed:\n{printed}"
            )
            return False
        print(f"  ok  {path}:{number}: {command.splitlines()[0][:100]}")
    return True


def run_file(path, args, failures):
    text = path.read_text(encoding="utf-8")
    relative = path.resolve().relative_to(REPO)
    found = list(blocks(text))
    python = (
        "python" in path.name
        or path.name == "cluster.md"
        or path.parent.name == "meshbool-py"
    )
    scripts = [(start, body) for info, start, body in found if python and info == "python"]
    consoles = [(start, body) for info, start, body in found if info == "console"]
    if not scripts and not consoles:
        return
    print(f"== {relative}")
    if args.keep:
        place = contextlib.nullcontext(tempfile.mkdtemp(prefix="meshbool-examples-"))
    else:
        place = tempfile.TemporaryDirectory(prefix="meshbool-examples-")
    with place as scratch:
        if args.keep:
            print(f"  (scratch directory kept: {scratch})")
        os.symlink(REPO / "docs", Path(scratch) / "docs")
        env = dict(os.environ)
        # `meshbool` from --bin; `python3` the interpreter of --python (a virtual
        # environment's, with docs/requirements.txt installed, for docs/render.py).
        python_dir = str(Path(args.python).parent) if os.sep in args.python else ""
        paths = [args.bin, python_dir, env.get("PATH", "")]
        env["PATH"] = os.pathsep.join(p for p in paths if p)
        for start, body in consoles:
            if not run_console(relative, start, body, scratch, env, failures):
                return
        if scripts:
            source = ""
            for start, body in scripts:
                # Line numbers of the Markdown file, for tracebacks.
                source += "\n" * (start - 1 - source.count("\n")) + "\n".join(body) + "\n"
            script = Path(scratch) / "examples.py"
            script.write_text(source, encoding="utf-8")
            code, printed = run([args.python, str(script)], scratch, env)
            if code != 0:
                why = f"ran past {TIMEOUT} s" if code is None else "failed"
                failures.append(f"{relative}: its Python examples {why}\n{printed}")
                return
            print(f"  ok  {relative}: {len(scripts)} Python blocks")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", default=str(REPO / "target" / "release"))
    venv = REPO / ".venv" / "bin" / "python"
    parser.add_argument("--python", default=str(venv) if venv.exists() else "python3")
    parser.add_argument("--keep", action="store_true")
    parser.add_argument("files", nargs="*", type=Path)
    args = parser.parse_args()
    args.bin = str(Path(args.bin).resolve())
    if os.sep in args.python:
        # Absolute, as the examples run elsewhere; not resolved, so a virtual environment's
        # interpreter stays itself (its link leads to the base interpreter).
        args.python = os.path.abspath(args.python)
    if not (Path(args.bin) / "meshbool").exists():
        sys.exit(f"error: no meshbool binary in {args.bin} (cargo build --release -p meshbool-cli)")
    files = args.files or [
        REPO / "README.md",
        *sorted((REPO / "docs").glob("*.md")),
        REPO / "crates" / "meshbool-py" / "README.md",
    ]
    failures = []
    for path in files:
        run_file(path.resolve(), args, failures)
    for failure in failures:
        print(f"FAILED {failure}", file=sys.stderr)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()

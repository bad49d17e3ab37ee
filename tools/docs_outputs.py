#!/usr/bin/env python3
"""Every `epicycle ...` command of docs/*.md and README.md, run into a folder, and two such folders
compared byte for byte with the timing and provenance fields masked (tools/check_docs_outputs.sh).

  docs_outputs.py list SOURCE_DIR                 the commands found, runnable or why not
  docs_outputs.py run SOURCE_DIR EXE OUT [--only REGEX] [--timeout S]
  docs_outputs.py diff OUT_A OUT_B                exit 1 if any masked file differs

A command is a code line (indented, or in backticks) that starts with `epicycle` or
`build/app/epicycle`; a trailing backslash joins the next line. A synopsis is not run: a command
with a placeholder (an upper-case word such as SCENE, FILE, N), an optional part `[...]`, a
choice `a|b` or `...`, or a shell variable; nor a fragment without its file, a command on a file
the repository does not hold, or one that writes outside its folder. Each command runs in its own folder OUT/NN-command
(scene paths made absolute, outputs where the command puts them), with its stdout, stderr and exit
code beside. The influence tables come from $EPICYCLE_CACHE_DIR (give both builds the same one).

Masked before comparing (they differ between two runs of one build): JSON keys named provenance or
seconds, ending in _seconds/_s/_ms/_over_wall, or holding _seconds_; CSV comment lines (# provenance) and columns named *_s,
*_ms, *seconds; in text, numbers followed by s, ms, cases/s or positions/s, `wall`/`cpu`
times and a speed sweep's CPU column, and whether an influence table was built or loaded from the
cache; a study's rows and a speed sweep's are compared in sorted order (their threads append them
as cases or speeds complete).
"""
import json
import os
import re
import shlex
import subprocess
import sys
import time

CODE = re.compile(r"^(?:    |\t)\s*((?:build/app/)?epicycle\s.*)$")
TICK = re.compile(r"`((?:build/app/)?epicycle\s[^`]+)`")


def commands(source):
    files = sorted(
        os.path.join(source, "docs", f)
        for f in os.listdir(os.path.join(source, "docs"))
        if f.endswith(".md")
    ) + [os.path.join(source, "README.md")]
    found = []
    for path in files:
        lines = open(path, encoding="utf-8").read().splitlines()
        i = 0
        while i < len(lines):
            line = lines[i]
            m = CODE.match(line) or re.match(r"^((?:build/app/)?epicycle\s.*\\)$", line)
            texts = [m.group(1)] if m else TICK.findall(line)
            start = i
            for text in texts:
                while text.rstrip().endswith("\\") and i + 1 < len(lines):
                    i += 1
                    text = text.rstrip()[:-1] + " " + lines[i].strip()
                text = re.sub(r"\s+#.*$", "", text).strip()
                found.append((os.path.relpath(path, source), start + 1, text))
            i += 1
    seen, out = set(), []
    for where, line, text in found:
        if text in seen:
            continue
        seen.add(text)
        out.append((where, line, text))
    return out


def why_not(text):
    words = shlex.split(text, posix=True) if text.count('"') % 2 == 0 else text.split()
    if len(words) < 2:
        return "no subcommand"
    for w in words[1:]:
        if re.search(r"[\[\]|]|\.\.\.|\$", w):
            return f"synopsis ({w})"
        bare = w.split("=")[-1]
        if re.fullmatch(r"[A-Z][A-Z_0-9]*(/[A-Z])?", bare):
            return f"placeholder ({w})"
    if "--help" in words:
        return None
    names = {"study", "merge", "dynamic", "modes", "quasistatic", "stiffness", "contact",
             "compare", "solve", "stability", "geometry", "contacts"}
    args = [w for i, w in enumerate(words[1:], 1)
            if not w.startswith("-") and w not in names and not words[i - 1].startswith("-")]
    if not args:
        return "a fragment (no file given)"
    if any(w.startswith("/") for w in words[1:]):
        return "writes outside its folder"
    if not any(w.startswith(("scenes/", "verification/")) for w in args):
        return f"a file the repository does not hold ({args[0]})"
    return None


def run(source, exe, out, only, timeout):
    os.makedirs(out, exist_ok=True)
    total = 0.0
    for k, (where, line, text) in enumerate(commands(source)):
        reason = why_not(text)
        if reason or (only and not re.search(only, text)):
            continue
        words = shlex.split(text)[1:]
        words = [os.path.join(source, w) if w.startswith(("scenes/", "verification/")) else w
                 for w in words]
        name = re.sub(r"[^A-Za-z0-9]+", "_", " ".join(shlex.split(text)[1:]))[:80]
        folder = os.path.join(out, f"{k:03d}-{name}")
        os.makedirs(folder, exist_ok=True)
        t0 = time.monotonic()
        with open(os.path.join(folder, "stdout.txt"), "wb") as so, \
                open(os.path.join(folder, "stderr.txt"), "wb") as se:
            try:
                # argv[0] "epicycle" whichever build runs: the usage lines name it.
                rc = subprocess.run(["epicycle"] + words, executable=exe, cwd=folder, stdout=so,
                                    stderr=se, stdin=subprocess.DEVNULL,
                                    timeout=timeout).returncode
            except subprocess.TimeoutExpired:
                rc = "timeout"
        seconds = time.monotonic() - t0
        total += seconds
        with open(os.path.join(folder, "command.txt"), "w") as f:
            f.write(f"{where}:{line}: {text}\nexit {rc}\n")
        print(f"{seconds:8.1f} s  exit {rc}  {where}:{line}: {text}", flush=True)
    print(f"{total:.1f} s in all")


NUMBER = r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?"


def mask_text(data):
    text = data.decode("utf-8", "replace")
    # The influence-table cache: the first of two runs builds what the second loads.
    text = re.sub(r"(built and written to|loaded from) '", "from the cache '", text)
    text = re.sub(NUMBER + r"(\s*)(s|ms|cases/s|positions/s|steps/s)\b", r"T\1\2", text)
    text = re.sub(r"\((?:" + NUMBER + r")(\s*)(cases/s|positions/s)", r"(T\1\2", text)
    text = re.sub(r"(wall|cpu|CPU|tables)\s+" + NUMBER, r"\1 T", text)
    return mask_sweep_table(text)


def mask_sweep_table(text):
    """The CPU seconds column of a speed sweep's table (sun rpm, K_gamma, K_v, mesh, TE amp,
    orbit, CPU s, status): the 7th field of a speed's line, the 6th when the speed has no mesh (it
    failed)."""
    out, in_table = [], False
    for line in text.split("\n"):
        fields = line.split()
        if "CPU s" in line and fields[:2] == ["sun", "rpm"]:
            in_table = True
        elif in_table and not fields:
            in_table = False
        elif in_table and len(fields) >= 7 and re.fullmatch(NUMBER, fields[0]):
            k = 5 if re.fullmatch(NUMBER, fields[3]) else 6
            line = re.sub(r"^((?:\s*\S+){%d}\s+)%s" % (k, NUMBER), r"\1T", line)
        out.append(line)
    return "\n".join(out)


TIMED = re.compile(r"(^provenance$|_seconds$|_seconds_|_s$|_ms$|^seconds$|_over_wall$)")


def mask_json(value):
    if isinstance(value, dict):
        return {k: mask_json(v) for k, v in value.items() if not TIMED.search(k)}
    if isinstance(value, list):
        return [mask_json(v) for v in value]
    return value


def mask_csv(data):
    lines = [l for l in data.decode("utf-8", "replace").splitlines() if not l.startswith("#")]
    if not lines:
        return ""
    head = lines[0].split(",")
    keep = [i for i, h in enumerate(head) if not TIMED.search(h)]
    if len(keep) == len(head):
        return "\n".join(lines)
    out = []
    for l in lines:  # the timed columns hold numbers: a split on commas is exact for them
        cells = l.split(",")
        if len(cells) != len(head):
            out.append(l)
            continue
        out.append(",".join(cells[i] for i in keep))
    return "\n".join(out)


def masked(path):
    data = open(path, "rb").read()
    if path.endswith(".json"):
        try:
            return json.dumps(mask_json(json.loads(data)), indent=1, sort_keys=True)
        except ValueError:
            return mask_text(data)
    if path.endswith(".csv"):
        text = mask_csv(data)
        name = os.path.basename(path)
        if name.startswith("study_") or name == "speed_sweep.csv":
            # A study's rows and a speed sweep's are appended as cases or speeds complete on
            # their threads: their order is not the run's result (the merge and the summaries
            # sort them by case id or speed).
            head, *rows = text.split("\n")
            text = "\n".join([head] + sorted(rows))
        return text
    if path.endswith((".txt", ".svg", ".md")):
        return mask_text(data) if path.endswith(".txt") else data.decode("utf-8", "replace")
    return data


def diff(a, b):
    names = set()
    for root in (a, b):
        for d, _, fs in os.walk(root):
            for f in fs:
                names.add(os.path.relpath(os.path.join(d, f), root))
    differ = 0
    for n in sorted(names):
        pa, pb = os.path.join(a, n), os.path.join(b, n)
        if not os.path.exists(pa) or not os.path.exists(pb):
            print(f"only in {'B' if os.path.exists(pb) else 'A'}: {n}")
            differ += 1
            continue
        if masked(pa) != masked(pb):
            print(f"differs (masked): {n}")
            differ += 1
    print(f"{len(names)} files, {differ} differ after masking")
    return 1 if differ else 0


def main(argv):
    if len(argv) >= 2 and argv[0] == "list":
        for where, line, text in commands(argv[1]):
            reason = why_not(text)
            print(f"{'skip: ' + reason if reason else 'run'}\t{where}:{line}\t{text}")
        return 0
    if len(argv) >= 4 and argv[0] == "run":
        only, timeout = None, 3600.0
        rest = argv[4:]
        while rest:
            if rest[0] == "--only" and len(rest) > 1:
                only, rest = rest[1], rest[2:]
            elif rest[0] == "--timeout" and len(rest) > 1:
                timeout, rest = float(rest[1]), rest[2:]
            else:
                print(f"docs_outputs: unknown option {rest[0]}", file=sys.stderr)
                return 2
        run(os.path.abspath(argv[1]), os.path.abspath(argv[2]), os.path.abspath(argv[3]), only,
            timeout)
        return 0
    if len(argv) == 3 and argv[0] == "diff":
        return diff(argv[1], argv[2])
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""The documentation's own check (run by `make test`): in every Markdown file of the project,
every relative link resolves, every case file named exists, every command shown in a code
block parses (its command exists, its options are the ones `ryushi help COMMAND` lists, its
case loads with its --set overrides, the validations it names exist), and no file is longer
than 600 lines. And what the validation report says of each validation holds: the cases and
the reference its manifest (validation/NAME.yaml) names exist, and its `make_test` lists
exactly the tests that read its tolerances.

    python3 tests/docs/check_docs.py SOURCE_DIR RYUSHI

Exit status 0 when all holds; 1 with each problem as FILE:LINE: what.
"""
import glob
import os
import re
import shlex
import subprocess
import sys

import yaml

MAX_LINES = 600
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
CASE = re.compile(r"(?<![\w/.-])(cases/[\w./-]+\.(?:yaml|stl))")
COMMAND = re.compile(r"^\s*(?:\$\s+)?(?:[A-Z_]+=\S+\s+)*(?:\./)?(?:build/)?ryushi(?:-mpi)?\s+(.*)$")


def markdown_files(root):
    out = subprocess.run(["git", "-C", root, "ls-files", "--cached", "--others",
                          "--exclude-standard", "*.md"], capture_output=True, text=True,
                         check=True).stdout.split()
    return sorted(f for f in out if os.path.exists(os.path.join(root, f)))


class Checker:
    def __init__(self, root, binary):
        self.root, self.binary = root, binary
        self.problems = []
        self.helps = {}
        self.loaded = {}
        self.validations = None

    def bad(self, where, what):
        self.problems.append("%s: %s" % (where, what))

    def help_text(self, command):
        if command not in self.helps:
            args = [command, "--help"] if command == "validate" else ["help", command]
            r = subprocess.run([self.binary] + args, capture_output=True, text=True)
            self.helps[command] = r.stdout if r.returncode == 0 else None
        return self.helps[command]

    def validation_names(self):
        if self.validations is None:
            r = subprocess.run([self.binary, "validate", "--list"], capture_output=True,
                               text=True, cwd=self.root)
            self.validations = {line.split()[0] for line in r.stdout.splitlines() if line}
            self.validations.add("all")
        return self.validations

    def case_loads(self, case, sets):
        """`ryushi info CASE --set ...` succeeds (the case file and its overrides are sound)."""
        key = (case, tuple(sets))
        if key not in self.loaded:
            cmd = [self.binary, "info", case]
            for s in sets:
                cmd += ["--set", s]
            try:
                r = subprocess.run(cmd, capture_output=True, text=True, cwd=self.root,
                                   timeout=120)
                self.loaded[key] = None if r.returncode == 0 else (
                    r.stderr.strip().splitlines() or ["exit %d" % r.returncode])[-1]
            except subprocess.TimeoutExpired:
                self.loaded[key] = None  # it loads; setting it up is merely slow
        return self.loaded[key]

    def command(self, where, text):
        try:
            words = shlex.split(text, comments=True)
        except ValueError as e:
            self.bad(where, "command does not parse as shell words: %s" % e)
            return
        if not words:
            return
        # only the first command of a pipeline or a list
        for i, w in enumerate(words):
            if w in ("|", "&&", ";", "||", ">", "2>", ">>") or w.startswith((">", "2>")):
                words = words[:i]
                break
        if any("$" in w or "<" in w or w.endswith("...") for w in words):
            return  # a template, not a command to run as is
        sub, args = words[0], words[1:]
        if sub in ("--help", "-h", "--version"):
            return
        help_text = self.help_text(sub)
        if help_text is None:
            self.bad(where, "no command 'ryushi %s' (ryushi --help)" % sub)
            return
        positional, sets = [], []
        i = 0
        while i < len(args):
            a = args[i]
            if a.startswith("-"):
                opt = a.split("=", 1)[0]
                if not re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(opt), help_text):
                    self.bad(where, "ryushi %s: option %s is not in `ryushi help %s`" % (
                        sub, opt, sub))
                if opt == "--set":
                    if "=" in a[2:]:
                        sets.append(a.split("=", 1)[1])
                    elif i + 1 < len(args):
                        sets.append(args[i + 1])
                        i += 1
                elif opt in ("-o", "--output", "--threads", "--restart", "--root", "--into") \
                        and "=" not in a:
                    i += 1
            else:
                positional.append(a)
            i += 1
        if sub in ("run", "info") and positional:
            case = positional[0]
            if case.startswith("cases/") and os.path.exists(os.path.join(self.root, case)):
                err = self.case_loads(case, sets)
                if err:
                    self.bad(where, "`ryushi %s`: the case does not load: %s" % (text, err))
        if sub == "validate":
            for name in positional:
                if name not in self.validation_names():
                    self.bad(where, "no validation '%s' (ryushi validate --list)" % name)

    def check_file(self, rel):
        path = os.path.join(self.root, rel)
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        if len(lines) - 1 > MAX_LINES:
            self.bad(rel, "%d lines, more than %d: split it" % (len(lines) - 1, MAX_LINES))
        fence, pending = None, ""
        for n, line in enumerate(lines, 1):
            where = "%s:%d" % (rel, n)
            m = re.match(r"^\s*(```+|~~~+)(\w*)", line)
            if m:
                fence, pending = None if fence else (m.group(1), m.group(2)), ""
                continue
            if fence:
                if fence[1] in ("", "sh", "bash", "console", "shell"):
                    if line.rstrip().endswith("\\"):  # a command continued on the next line
                        pending += line.rstrip()[:-1] + " "
                        continue
                    c = COMMAND.match(pending + line)
                    pending = ""
                    if c:
                        self.command(where, c.group(1))
            else:
                for target in LINK.findall(line):
                    self.link(where, rel, target)
            for case in CASE.findall(line):
                if not os.path.exists(os.path.join(self.root, case)) and "NAME" not in case:
                    self.bad(where, "no case file %s" % case)

    def link(self, where, rel, target):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
            return
        target = target.split("#", 1)[0]
        full = os.path.normpath(os.path.join(self.root, os.path.dirname(rel), target))
        if not os.path.exists(full):
            self.bad(where, "link to %s, which does not exist" % target)


def manifest_readers(root):
    """{validation: the tests (ctest names) that read its tolerances}."""
    readers = {}
    for path in glob.glob(os.path.join(root, "tests", "physics", "*.c")) + \
            glob.glob(os.path.join(root, "tests", "python", "*.py")):
        text = open(path, encoding="utf-8").read()
        names = set(re.findall(r'manifest_tol\(\w+, "(\w+)"', text))
        names |= set(re.findall(r'\btol\("(\w+)"', text))
        names |= set(re.findall(r'tolerance\(\w+, "(\w+)"', text))
        base = os.path.basename(path)
        test = "python.pytest" if base.endswith(".py") else "physics." + base[:-2]
        for n in names:
            readers.setdefault(n, set()).add(test)
    return readers


def check_manifests(checker, root):
    readers = manifest_readers(root)
    for path in sorted(glob.glob(os.path.join(root, "validation", "*.yaml"))):
        rel = os.path.relpath(path, root)
        name = os.path.basename(path)[:-5]
        m = yaml.safe_load(open(path, encoding="utf-8"))
        for case in m.get("cases") or []:
            if not os.path.exists(os.path.join(root, case)):
                checker.bad(rel, "no case file %s" % case)
        ref = m.get("reference")
        for r in ([] if ref in (None, "none") else ref if isinstance(ref, list) else [ref]):
            if not os.path.exists(os.path.join(root, r)):
                checker.bad(rel, "no reference file %s" % r)
        listed = set(m.get("make_test") or [])
        if listed != readers.get(name, set()):
            checker.bad(rel, "make_test lists %s; the tests that read its tolerances are %s" % (
                sorted(listed), sorted(readers.get(name, set()))))


def main():
    root, binary = sys.argv[1], os.path.abspath(sys.argv[2])
    checker = Checker(root, binary)
    files = markdown_files(root)
    for rel in files:
        checker.check_file(rel)
    check_manifests(checker, root)
    for p in checker.problems:
        print(p)
    print("docs: %d files, %d commands' cases loaded, %d problem(s)" % (
        len(files), len(checker.loaded), len(checker.problems)))
    return 1 if checker.problems else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""The function bodies of the given C++ files that are longer than a limit.

    python3 tools/check_function_length.py LIMIT ALLOWED FILE...

A function body runs from the line of its opening brace to the line of its closing brace (both
counted). Functions are found by brace matching with comments, string, character and raw string
literals skipped: a brace at namespace, class, struct, union or enum scope (or `extern "C"`) opens
a body unless the text before it is an initializer (`= {`, `T x{`) or a type definition; blocks
inside a body (lambdas, loops, local classes) belong to it. ALLOWED is a comma-separated list of
FILE:FUNCTION pairs that may be longer. Prints "FILE:LINE: FUNCTION: N lines (limit LIMIT)" for
every other body over the limit and the number of bodies checked; exits 1 if one is over.
"""
import re
import sys

TYPE_HEAD = re.compile(r"\b(namespace|class|struct|union|enum)\b[^()]*$|extern\s+\"C\"\s*$")
NAME = re.compile(r"([A-Za-z_~][A-Za-z_0-9:<>,~ ]*?)\s*\(")


def strip(text):
    """The text with comments and literals blanked (line breaks kept, so that lines count)."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            k = text.find("(", i + 2)
            delim = ")" + text[i + 2:k] + '"'
            j = text.find(delim, k + 1)
            j = n if j < 0 else j + len(delim)
            out.append('""' + "\n" * text.count("\n", i, j))
            i = j
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):
            # a string or character literal (a digit separator 1'000 is not one)
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def bodies(text):
    """(name, first line, line count) of every function body in the C++ text."""
    s = strip(text)
    # Preprocessor lines (a #define's braces) are not code of a scope.
    s = re.sub(r"(?m)^[ \t]*#(?:[^\n\\]|\\\n|\\.)*", lambda m: "\n" * m.group(0).count("\n"), s)
    scopes = []  # per open brace: "scope" (namespace, type), "body" or "block"
    head_start = 0  # where the text of the declaration before the next brace begins
    body_start = None
    line = 1
    found = []
    for i, c in enumerate(s):
        if c == "\n":
            line += 1
        if c == "{":
            in_body = any(k == "body" for k in scopes)
            if in_body:
                scopes.append("block")
            else:
                head = s[head_start:i].strip()
                if re.search(r"\)[^(){};]*:(?!:)[^{};]*[A-Za-z_0-9]$", head) and not TYPE_HEAD.search(head):
                    scopes.append("init")  # a member's braces in a constructor's initializer list
                    continue
                if TYPE_HEAD.search(head) or not head:
                    scopes.append("scope")
                elif head.endswith("=") or re.search(r"[A-Za-z_0-9>\]]\s*$", head) and "(" not in head:
                    scopes.append("data")  # an initializer: = { ... } or T x{ ... }
                else:
                    m = None
                    for m in NAME.finditer(head.split("=")[0] if "operator" not in head else head):
                        break
                    name = m.group(1).split()[-1] if m else head[:40]
                    scopes.append("body")
                    body_start = (name, line)
            head_start = i + 1
        elif c == "}":
            kind = scopes.pop() if scopes else "scope"
            if kind == "init":
                continue  # the constructor's declaration goes on to its body
            if kind == "body":
                name, first = body_start
                found.append((name, first, line - first + 1))
            head_start = i + 1
        elif c == ";" and not any(k in ("body", "data") for k in scopes):
            head_start = i + 1
        elif c == ":" and not any(k in ("body", "data") for k in scopes):
            # access specifiers (public:) end a declaration's text; a :: or a constructor's
            # initializer list does not (the name comes before them)
            if s[head_start:i].strip() in ("public", "private", "protected"):
                head_start = i + 1
    return found


def main():
    limit = int(sys.argv[1])
    allowed = {a for a in sys.argv[2].split(",") if a}
    failures = checked = 0
    for path in sys.argv[3:]:
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for name, first, count in bodies(text):
            checked += 1
            short = name.split("::")[-1]
            if count > limit and f"{path}:{short}" not in allowed:
                print(f"{path}:{first}: {name}: {count} lines (limit {limit})")
                failures += 1
    print(f"{checked} function bodies checked, {failures} over {limit} lines")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())

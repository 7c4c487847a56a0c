#!/usr/bin/env python3
"""Checks the relative links of the documentation: the top-level Markdown files, everything
under docs/, and the built guide (docs/book/book/, from `mdbook build docs/book`).

A relative link must name a file or directory that exists, and its #anchor a heading of the
target (Markdown: the heading's GitHub/mdBook slug; HTML: an element's id). Images must exist.
Links to other sites are not fetched (CI has no business depending on them). Exits 1 and lists
every broken link, or prints how many links it checked.

    python3 scripts/check_links.py [--no-html]
"""

import html.parser
import re
import sys
import unicodedata
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARKDOWN = ["README.md", "BENCHMARKS.md", "ARCHITECTURE.md", "CHANGELOG.md", "web/README.md"]
BOOK_HTML = ROOT / "docs" / "book" / "book"

FENCE = re.compile(r"^(```|~~~).*?^\1[^\n]*$", re.S | re.M)
INLINE_CODE = re.compile(r"`+[^`\n]*`+")
COMMENT = re.compile(r"<!--.*?-->", re.S)
# [text](target) and ![alt](target), the target up to whitespace or the closing parenthesis.
MD_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HTML_ATTR = re.compile(r"""(?:src|href)\s*=\s*["']([^"']+)["']""")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$", re.M)


def slug(heading: str) -> str:
    """The anchor GitHub and mdBook give a heading: lower case, inline markup dropped, every
    character that is not a letter, a digit, `-`, `_` or a space removed, spaces as `-`."""
    text = re.sub(r"`([^`]*)`", r"\1", heading)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"<[^>]+>", "", text)
    out = []
    for ch in text.strip().lower():
        if ch.isalnum() or ch in "-_":
            out.append(ch)
        elif ch.isspace():
            out.append("-")
        elif unicodedata.category(ch).startswith("L"):
            out.append(ch)
    return "".join(out)


def markdown_anchors(path: Path) -> set:
    text = FENCE.sub("", path.read_text(encoding="utf-8"))
    anchors, seen = set(), {}
    for match in HEADING.finditer(text):
        base = slug(match.group(2))
        count = seen.get(base, 0)
        seen[base] = count + 1
        anchors.add(base if count == 0 else f"{base}-{count}")
    return anchors


def is_external(target: str) -> bool:
    return re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I) is not None


def check_markdown(path: Path, problems: list) -> int:
    text = path.read_text(encoding="utf-8")
    text = COMMENT.sub("", FENCE.sub("", text))
    text = INLINE_CODE.sub("", text)
    targets = [m.group(1) for m in MD_LINK.finditer(text)]
    targets += [m.group(1) for m in HTML_ATTR.finditer(text)]
    for target in targets:
        if is_external(target):
            continue
        file_part, _, anchor = target.partition("#")
        resolved = (path.parent / file_part).resolve() if file_part else path
        where = f"{path.relative_to(ROOT)}: ({target})"
        if not resolved.exists():
            problems.append(f"{where}: no such file")
        elif anchor and resolved.suffix == ".md" and anchor not in markdown_anchors(resolved):
            problems.append(f"{where}: no heading with anchor #{anchor}")
    return len(targets)


class _Html(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if name == "id" and value:
                self.ids.add(value)
            if name in ("href", "src") and value:
                self.links.append(value)


def parse_html(path: Path, cache: dict) -> _Html:
    if path not in cache:
        parser = _Html()
        parser.feed(path.read_text(encoding="utf-8"))
        cache[path] = parser
    return cache[path]


def check_html(problems: list) -> int:
    cache, count = {}, 0
    for page in sorted(BOOK_HTML.glob("*.html")):
        for target in parse_html(page, cache).links:
            count += 1
            if is_external(target) or target.startswith("{{"):
                continue
            file_part, _, anchor = target.partition("#")
            file_part = file_part.split("?")[0]
            resolved = (page.parent / file_part).resolve() if file_part else page
            where = f"{page.relative_to(ROOT)}: ({target})"
            if not resolved.exists():
                problems.append(f"{where}: no such file")
            elif anchor and resolved.suffix == ".html":
                if anchor not in parse_html(resolved, cache).ids:
                    problems.append(f"{where}: no element with id #{anchor}")
    return count


def main() -> int:
    problems = []
    files = [ROOT / name for name in MARKDOWN if (ROOT / name).exists()]
    files += sorted((ROOT / "docs").rglob("*.md"))
    files = [f for f in files if BOOK_HTML not in f.parents]
    count = sum(check_markdown(f, problems) for f in files)
    html_count = 0
    if "--no-html" not in sys.argv:
        if not (BOOK_HTML / "index.html").exists():
            problems.append("docs/book/book/index.html: no built guide (run `mdbook build docs/book`)")
        else:
            html_count = check_html(problems)
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_links: {len(problems)} broken link(s)")
        return 1
    print(f"check_links: {count} Markdown links in {len(files)} files and {html_count} links of the built guide resolve")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""MkDocs hooks of `make docs` (mkdocs.yml).

- CHANGELOG.md, which lives at the top of the repository where a packager and GitHub expect it,
  becomes the site's changelog.md, and a page's link to it (`../CHANGELOG.md` from docs/,
  `../../CHANGELOG.md` from a section) is pointed there: the pages keep links that also work where
  the repository is browsed as files.
- A page path written in plain text, docs/design/vtd-nog.md (as the code comments write them too),
  becomes a link on the site when it names one of its pages; not inside code. (A path that names
  nothing stays text: tests/docs/check_docs.py fails on it.)
"""
from __future__ import annotations

import posixpath
import re
from pathlib import Path

from mkdocs.structure.files import File, Files

ROOT = Path(__file__).resolve().parents[2]
EXTRA = {"CHANGELOG.md": "changelog.md"}   # repository path -> the site's page
LINK = re.compile(r"\]\(([^)\s#]+)(#[^)\s]*)?\)")
PLAIN = re.compile(r"(?<![\w./\[-])docs/([\w/-]+\.md)\b")
CODE = re.compile(r"(`+)(?:.+?)\1")   # an inline code span


def on_files(files: Files, config) -> Files:
    for repo_path, page in EXTRA.items():
        files.append(File.generated(config, page, abs_src_path=str(ROOT / repo_path)))
    return files


def _repo_dir(src_uri: str) -> str:
    """Where the page lives in the repository (the folder its relative links start from)."""
    for repo_path, page in EXTRA.items():
        if src_uri == page:
            return posixpath.dirname(repo_path)
    return posixpath.join("docs", posixpath.dirname(src_uri))


def on_page_markdown(markdown: str, page, config, files) -> str:
    here = _repo_dir(page.file.src_uri)
    site_dir = posixpath.dirname(page.file.src_uri) or "."

    def sub(m: re.Match) -> str:
        target = m.group(1)
        if re.match(r"^[a-z]+:", target) or target.startswith("/"):
            return m.group(0)
        repo = posixpath.normpath(posixpath.join(here, target))
        if repo in EXTRA:
            site = EXTRA[repo]
        elif repo.startswith("docs/"):
            site = repo[len("docs/"):]
        else:
            return m.group(0)   # outside the site: mkdocs --strict reports it
        return f"]({posixpath.relpath(site, site_dir)}{m.group(2) or ''})"
    def to_link(p: re.Match) -> str:
        if files.get_file_from_path(p.group(1)) is None:
            return p.group(0)   # not a page of the site (docs/README.md); check_docs.py checks it exists
        return f"[docs/{p.group(1)}]({posixpath.relpath(p.group(1), site_dir)})"

    def plain(text: str) -> str:
        out, last = [], 0
        for m in CODE.finditer(text):
            out.append(PLAIN.sub(to_link, text[last:m.start()]))
            out.append(m.group(0))
            last = m.end()
        out.append(PLAIN.sub(to_link, text[last:]))
        return "".join(out)

    lines, fenced = [], False
    for line in LINK.sub(sub, markdown).split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
        lines.append(line if fenced or line.lstrip().startswith("```") else plain(line))
    return "\n".join(lines)

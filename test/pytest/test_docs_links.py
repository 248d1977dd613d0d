"""The documentation a user's clone carries: README.md, CHANGELOG.md and docs/*.md.

- Every relative Markdown link (`[text](path)`, `![alt](path)`, with or without `#anchor`) names a file or folder
  of the repository, and an anchor into a Markdown page names one of that page's headings (GitHub's slugs).
- No page of docs/ or the README cites an issue number or a work log: docs describe the product as it is.
"""

import re
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PAGES = [REPO / "README.md", REPO / "CHANGELOG.md"] + sorted((REPO / "docs").glob("*.md"))
PRODUCT_PAGES = [REPO / "README.md"] + sorted((REPO / "docs").glob("*.md"))

LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
FENCE = re.compile(r"^\s*(```|~~~)")
CODE_SPAN = re.compile(r"`[^`]*`")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")
# An issue cited by number: "issue 10", "issues 13, 10", "(#12)", "issue #4".
ISSUE = re.compile(r"\bissues?\s+#?\d+|\(#\d+\)|\bPR\s+#?\d+", re.IGNORECASE)
# A work log: a session, a numbered pass, something merged or tried and dropped.
WORK_LOG = re.compile(
    r"\bthis session\b|\b(first|second|third|fourth|fifth) pass\b|\bnot kept\b|\bthis branch\b|"
    r"\bafter every branch\b|\bUntil 20\d\d-\d\d-\d\d|\bAn earlier version\b|\bthe lead\b",
    re.IGNORECASE,
)


def prose_lines(text):
    """(line number, line) outside fenced code blocks, with inline code spans blanked."""
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, CODE_SPAN.sub("``", line)


def slug(heading):
    """GitHub's anchor for a heading: lower case, markup and punctuation dropped, spaces to hyphens."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link keeps its text
    text = text.replace("`", "").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(page):
    found, seen = set(), {}
    fenced = False
    for line in page.read_text().splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        m = None if fenced else HEADING.match(line)
        if m:
            base = slug(m.group(1))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f"{base}-{n}")
    return found


def relative_links(page):
    for number, line in prose_lines(page.read_text()):
        for target in LINK.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.IGNORECASE):  # http:, https:, mailto:, file:
                continue
            yield number, target


def broken_links(page):
    problems = []
    for number, target in relative_links(page):
        path_part, _, anchor = target.partition("#")
        dest = (page.parent / path_part).resolve() if path_part else page
        where = f"{page.relative_to(REPO)}:{number}: ({target})"
        if not dest.exists():
            problems.append(f"{where} names no file of the repository")
        elif REPO not in dest.parents and dest != REPO:
            problems.append(f"{where} points outside the repository")
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            problems.append(f"{where}: no heading of {dest.relative_to(REPO)} has the anchor #{anchor}")
    return problems


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_every_relative_link_names_a_file_of_the_repository(page):
    problems = broken_links(page)
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("page", PRODUCT_PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_no_issue_numbers_or_work_log_in_the_docs(page):
    hits = [
        f"{page.relative_to(REPO)}:{n}: {line.strip()}"
        for n, line in prose_lines(page.read_text())
        if ISSUE.search(line) or WORK_LOG.search(line)
    ]
    assert not hits, "docs describe the product, not its history:\n" + "\n".join(hits)


def test_the_checks_find_what_they_are_for(tmp_path, monkeypatch):
    """The link check against a page with a good link, a missing file, a link out of the repository and a wrong
    anchor; the issue and work-log patterns against sentences that must and must not match."""
    monkeypatch.setattr(sys.modules[__name__], "REPO", tmp_path)
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "b.md").write_text("# Title\n## The rviz configuration (`launch/x.rviz`)\n## Title\n")
    page = tmp_path / "docs" / "a.md"
    page.write_text(
        "[ok](b.md#the-rviz-configuration-launchxrviz) [ok2](b.md#title-1) [self](#top)\n"
        "# Top\n[gone](missing.md)\n[out](../../etc/passwd)\n[anchor](b.md#nowhere)\n"
        "```\n[in code](nothing.md)\n```\n`[span](nothing.md)` [web](https://example.org/x)\n"
    )
    problems = broken_links(page)
    assert len(problems) == 3, problems
    assert "missing.md" in problems[0] and "no file" in problems[0]
    assert "passwd" in problems[1]
    assert "#nowhere" in problems[2]
    for bad in (
        "as issue 10 measured",
        "(#12)",
        "issues 13, 10",
        "in this session",
        "the fourth pass",
        "Tried and not kept:",
        "(Until 2026-11-23 the frame",
        "An earlier version solved it",
    ):
        assert ISSUE.search(bad) or WORK_LOG.search(bad), bad
    for good in ("the sonar equation (thesis 5.4.1)", "12 passed in 25.9 s", "`--passes 2`", "a tissue 10 mm"):
        assert not (ISSUE.search(good) or WORK_LOG.search(good)), good

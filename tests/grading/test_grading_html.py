"""report.html and the submissions' pages (grading/html_report.py) on a synthetic class
with hostile names and messages: what submissions wrote is text (in the files, and in a
real headless Chromium: nothing runs, no console error, no dialog), the policy allows
only the inline script and style, the facts are report.md's, and the submissions' table
sorts by the column clicked (numbers by value). The browser tests skip, with one line,
where there is no Chromium (./make.sh installs Debian's where it can)."""

from __future__ import annotations

import base64
import hashlib
import re
import sqlite3
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlparse

import pytest

from grading.html_report import write_html_report
from grading.markdown import report_text
from grading.similar import Pair
from grading.store import Store
from grading_fixtures import HOSTILE_NAME, HOSTILE_TEXT, SYNTHETIC, synthetic_results
from tests.conftest import unit_sample
from tests.validator.browser import Chromium, find_chromium

CHROMIUM = find_chromium()
browser_test = pytest.mark.skipif(CHROMIUM is None, reason="no Chromium: ./make.sh installs "
                                  "Debian's chromium where it can (apt-get, as root)")
PAIRS = [Pair("alice", HOSTILE_NAME, "identical answers", "on 1 of 3 " + HOSTILE_TEXT, 0.5)]


class Parsed(HTMLParser):
    """A page's elements (tag, attributes) and its text, as a browser's parser sees them."""

    def __init__(self, page: str):
        super().__init__(convert_charrefs=True)
        self.tags: list[tuple[str, dict]] = []
        self.text: list[str] = []
        self.raw: dict[str, list[str]] = {}
        self.open: list[str] = []
        self.feed(page)

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))
        self.open.append(tag)

    def handle_endtag(self, tag):
        if self.open and self.open[-1] == tag:
            self.open.pop()

    def handle_data(self, data):
        if self.open and self.open[-1] in ("script", "style"):
            self.raw.setdefault(self.open[-1], []).append(data)
        else:
            self.text.append(data)


@pytest.fixture(scope="module")
def written(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("html")
    write_html_report(synthetic_results(out), PAIRS)
    return out


def pages(out: Path) -> list[Path]:
    return [out / "report.html", *sorted((out / "html").glob("*/index.html"))]


def test_each_submission_has_a_page_and_the_class_report_links_it(written):
    assert sorted(path.parent.name for path in pages(written)[1:]) == sorted(SYNTHETIC)
    parsed = Parsed((written / "report.html").read_text())
    linked = {unquote(a["href"]) for tag, a in parsed.tags if tag == "a" and "href" in a
              and a["href"].startswith("html/")}
    assert linked == {f"html/{name}/index.html" for name in SYNTHETIC}


def test_what_submissions_wrote_is_text_in_every_page(written):
    told = {name for name, letters in SYNTHETIC.items() if set(letters) & set("ctb")}
    for path in pages(written):
        parsed = Parsed(path.read_text())
        tags = [tag for tag, _ in parsed.tags]
        assert tags.count("script") == 1 and tags.count("style") == 1, path
        assert "img" not in tags and ("bold" in parsed.text) is False, path
        assert not [name for _, attrs in parsed.tags for name in attrs if name.startswith("on")]
        text = "".join(parsed.text)
        assert (HOSTILE_TEXT in text) == (path.parent.name in told or path.name == "report.html")
    shown = "".join(Parsed((written / "report.html").read_text()).text)
    assert HOSTILE_NAME in shown and HOSTILE_TEXT in shown


def test_the_policy_allows_only_the_inline_script_and_style(written):
    for path in pages(written):
        page = path.read_text()
        policy = re.search(r'http-equiv="Content-Security-Policy" content="([^"]*)"', page)[1]
        parsed = Parsed(page)
        hashes = {kind: "'sha256-" + base64.b64encode(hashlib.sha256(
            "".join(parsed.raw[kind]).encode()).digest()).decode() + "'"
            for kind in ("script", "style")}
        frames = "'self'" if path.name == "index.html" else "'none'"
        assert policy == (f"default-src 'none'; script-src {hashes['script']}; style-src "
                          f"{hashes['style']}; img-src data:; frame-src {frames}")


def test_the_class_report_shows_report_mds_facts(written):
    markdown = report_text(synthetic_results(written), PAIRS)
    shown = " ".join(" ".join(Parsed((written / "report.html").read_text()).text).split())
    summary = re.search(r"^\d+ submissions; scores out of .*$", markdown, re.M)[0]
    assert summary in shown
    for cell in re.findall(r"\d+/\d+ \(\d+%\)", markdown):  # the pass rates
        assert cell in shown
    failing = markdown[markdown.index("### Failing runs"):markdown.index("### Similar")]
    counts = re.findall(r"^\| (invalid \(\w+\)|build failed|timed out)[^|]*\| (\d+) \|",
                        failing, re.M)
    assert len(counts) == 4
    for label, count in counts:
        assert re.search(re.escape(label) + r"[^|]*? " + count + " ", shown), label


def test_a_store_without_views_gets_the_column_and_keeps_its_rows(tmp_path):
    from grading.store import _SCHEMA
    before = re.sub(r"\n *view TEXT,[^\n]*", "", _SCHEMA)  # the store before views
    assert before != _SCHEMA
    db = sqlite3.connect(tmp_path / "grades.sqlite")
    db.executescript(before + "INSERT INTO runs (submission, problem, mode, verdict, valid, "
                     "pdf) VALUES ('a', 'p.sw', 'point', 'invalid', 0, 'x.pdf');")
    db.close()
    store = Store(tmp_path)
    try:
        assert [(row["pdf"], row["view"]) for row in store.runs()] == [("x.pdf", None)]
        store.add_run({"submission": "b", "problem": "p.sw", "mode": "point", "repeat": 0,
                       "verdict": "invalid", "valid": 0, "view": "v.html"})
        assert [row["view"] for row in store.runs()] == [None, "v.html"]
    finally:
        store.close()


# ----- in a browser -----------------------------------------------------------------------

@pytest.fixture(scope="module")
def browser():
    with Chromium(CHROMIUM, 1200, 900) as chromium:
        yield chromium


def load(browser: Chromium, path: Path) -> None:
    browser.open(path.as_uri())
    browser.wait_for(lambda: browser.evaluate("window.rrtReport && window.rrtReport.ready"))


def trouble(browser: Chromium) -> list[str]:
    """Console errors and dialogs (an alert() would open one) since the page was opened."""
    dialogs = [event["params"].get("message", "") for event in browser.events
               if event.get("method") == "Page.javascriptDialogOpening"]
    return browser.console_errors() + [f"dialog: {message}" for message in dialogs]


def click(browser: Chromium, selector: str) -> None:
    """A real click (the pointer pressed and released) at the middle of the element."""
    left, top, width, height = browser.evaluate(
        f"(() => {{ const e = document.querySelector({selector!r}); e.scrollIntoView("
        "{block: 'center'}); const r = e.getBoundingClientRect(); "
        "return [r.left, r.top, r.width, r.height]; })()")
    x, y = left + width / 2, top + height / 2
    for kind in ("mousePressed", "mouseReleased"):
        browser.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left",
                     clickCount=1)


def column(browser: Chromium, index: int) -> list[str]:
    """The submissions table's cells of one column, in the order shown."""
    return browser.evaluate(f"Array.from(document.querySelectorAll('table.sortable tbody tr'),"
                            f" r => r.cells[{index}].textContent)")


def sort_by(browser: Chromium, name: str) -> None:
    sorts = browser.evaluate("window.rrtReport.sorts")
    index = browser.evaluate("Array.from(document.querySelectorAll('table.sortable th'), "
                             f"h => h.textContent).indexOf({name!r})")
    click(browser, f"table.sortable th:nth-child({index + 1}) button")
    browser.wait_for(lambda: browser.evaluate("window.rrtReport.sorts") > sorts)


@browser_test
def test_the_class_report_loads_and_its_table_sorts_by_the_column_clicked(written, browser):
    load(browser, written / "report.html")
    assert trouble(browser) == []
    names = column(browser, 0)
    assert sorted(names) == sorted(SYNTHETIC) and len(names) == 7
    sort_by(browser, "score")  # by value: 66.7 before 100.0 (as text it would not be)
    scores = [float(cell) for cell in column(browser, 1)]
    assert scores == sorted(scores) and scores[-1] == 100.0
    sort_by(browser, "score")
    assert [float(cell) for cell in column(browser, 1)] == sorted(scores, reverse=True)
    assert browser.evaluate("document.querySelector('table.sortable th:nth-child(2)')"
                            ".getAttribute('aria-sort')") == "descending"
    sort_by(browser, "submission")  # natural order: erin9 before erin10
    shown = column(browser, 0)
    assert shown.index("erin9") == shown.index("erin10") - 1 and shown[0] == "alice"
    sort_by(browser, "median time, ours = x1")  # rows without one ("-") go last both ways
    assert column(browser, 9)[-2:] == ["-", "-"]
    times = [float(cell[1:]) for cell in column(browser, 9)[:-2]]
    assert times == sorted(times)
    sort_by(browser, "median time, ours = x1")
    assert column(browser, 9)[-2:] == ["-", "-"]
    assert [float(cell[1:]) for cell in column(browser, 9)[:-2]] == sorted(times, reverse=True)
    assert trouble(browser) == []


# Every page in the browser: in the unit run the class report's and those of the submissions
# whose texts are hostile (its name and a collision, a timeout, a failed build), the other
# pages in ./test.sh.
_FIRST = ["report.html", HOSTILE_NAME, "carol", "dave"]
PAGES = unit_sample([pytest.param(name, id="hostile-name" if name == HOSTILE_NAME else name)
                     for name in _FIRST + [name for name in SYNTHETIC if name not in _FIRST]],
                    keep=len(_FIRST))


@browser_test
@pytest.mark.parametrize("page", PAGES)
def test_hostile_names_and_messages_show_as_text_and_nothing_runs(written, browser, page):
    path = written / page if page == "report.html" else written / "html" / page / "index.html"
    load(browser, path)
    assert trouble(browser) == [], path
    assert browser.evaluate("[document.images.length, document.scripts.length, Array.from("
                            "document.querySelectorAll('b'), b => b.textContent)"
                            ".includes('bold')]") == [0, 1, False]
    shown = browser.evaluate("document.body.innerText")
    if page in (HOSTILE_NAME, "report.html"):
        assert HOSTILE_NAME in shown
    if page != HOSTILE_NAME:
        return
    assert browser.evaluate("document.querySelector('h1').textContent") == HOSTILE_NAME
    reason = browser.evaluate("document.querySelector('.reason').textContent")
    assert HOSTILE_TEXT in reason and reason.startswith("invalid (collision): ")
    href = browser.evaluate("document.querySelector('a').href")  # back to the class
    assert Path(unquote(urlparse(href).path)) == written / "report.html"
    view = browser.evaluate("document.querySelector('details.view iframe').dataset.src")
    assert (written / "html" / HOSTILE_NAME / unquote(view)).parent.name == HOSTILE_NAME

"""Pairs of submissions for a person to look at: their valid answers are byte for byte
the same on the same problem and mode (the same code run with the same seeds), or
their sources are near-identical (shared token shingles, leaving out what most of the
class shares, such as a course's template). A flag, never a change of score.

The sources are read from each submission's folder as handed in, bounded: regular
files only (no link is followed, no FIFO or device opened), hidden files and folders
skipped, binary files (a NUL byte) skipped, at most ``MAX_FILE_BYTES`` a file,
``MAX_BYTES`` and ``MAX_FILES`` a submission, ``MAX_DEPTH`` folders deep; of a
submission with more than ``MAX_SHINGLES`` shingles, the ``MAX_SHINGLES`` smallest
hashes stand for it (a bottom-k sketch: the same for the same text), so memory and
time stay bounded whatever a submission holds."""

from __future__ import annotations

import heapq
import math
import os
import re
import stat
from collections import Counter, defaultdict
from dataclasses import dataclass
from itertools import combinations
from pathlib import Path

from grading.scores import Key, Scored

SHINGLE = 6            # tokens a shingle
MIN_JACCARD = 0.8      # shared shingles over all of the pair's, to flag a pair
MIN_SHARED = 20        # and at least this many shared
MAX_FILE_BYTES = 256 << 10
MAX_BYTES = 1 << 20
MAX_FILES = 2000
MAX_DEPTH = 16
MAX_SHINGLES = 20000
MOST_ALIKE_FILES = 50  # the largest files of each compared for the evidence
LABELS_SHOWN = 6
_TOKEN = re.compile(r"\w+|[^\w\s]")


@dataclass(frozen=True)
class Pair:
    """Two submissions that look alike, and why."""

    first: str
    second: str
    kind: str       # "identical answers" or "near-identical sources"
    evidence: str   # what was found, in words
    strength: float  # for the order: the share of answers or shingles in common


def similar_pairs(submissions: Path, graded: list[Scored]) -> list[Pair]:
    """The pairs to look at, the strongest first in each kind."""
    answers = identical_answers(graded)
    kept = {}
    for one in graded:  # only each one's sketch is kept: memory stays bounded
        files = read_sources(submissions / one.name)
        chosen = sketch(files)
        kept[one.name] = {path: found & chosen for path, found in files.items()}
    sources = near_identical_sources(kept)
    return (sorted(answers, key=lambda p: -p.strength)
            + sorted(sources, key=lambda p: -p.strength))


def identical_answers(graded: list[Scored]) -> list[Pair]:
    """Pairs with a byte-identical valid answer on at least one problem and mode."""
    holders: dict[tuple[Key, str], set[str]] = defaultdict(set)
    solved: dict[str, set[Key]] = {}
    for one in graded:
        solved[one.name] = set()
        for k, rows in one.runs.items():
            for row in rows:
                if row["valid"] and row.get("output_sha256"):
                    holders[k, row["output_sha256"]].add(one.name)
                    solved[one.name].add(k)
    same: dict[tuple[str, str], set[Key]] = defaultdict(set)
    for (k, _), names in holders.items():
        for pair in combinations(sorted(names), 2):
            same[pair].add(k)
    pairs = []
    for (first, second), keys in same.items():
        both = solved[first] & solved[second]
        labels = [f"{problem} {mode}" for problem, mode in sorted(keys)]
        shown = ", ".join(labels[:LABELS_SHOWN]) + (", ..." if len(labels) > LABELS_SHOWN
                                                     else "")
        pairs.append(Pair(first, second, "identical answers",
                          f"the same valid output, byte for byte, on {len(keys)} of the "
                          f"{len(both)} problem-modes both solved: {shown}",
                          len(keys) / len(both)))
    return pairs


def shingles(text: str) -> set[int]:
    """The hashes of the text's runs of ``SHINGLE`` tokens (words, numbers, marks)."""
    tokens = _TOKEN.findall(text)
    return {hash(tuple(tokens[i:i + SHINGLE])) for i in range(len(tokens) - SHINGLE + 1)}


def read_sources(folder: Path) -> dict[str, set[int]]:
    """Each text file of a submission (relative path) and its shingles, within bounds."""
    found: dict[str, set[int]] = {}
    budget = MAX_BYTES
    try:
        walk = os.fwalk(folder, follow_symlinks=False)
        for top, dirs, files, top_fd in walk:
            depth = os.path.relpath(top, folder).count(os.sep)
            dirs[:] = [] if depth >= MAX_DEPTH else sorted(d for d in dirs
                                                           if not d.startswith("."))
            for name in sorted(files):
                if name.startswith(".") or len(found) >= MAX_FILES or budget <= 0:
                    continue
                data = _read_regular(name, top_fd, min(MAX_FILE_BYTES, budget))
                if data is not None and b"\0" not in data[:8192]:
                    budget -= len(data)
                    found[os.path.relpath(os.path.join(top, name), folder)] = shingles(
                        data.decode("utf-8", errors="replace"))
    except OSError:
        pass  # what could be read is compared
    return found


def _read_regular(name: str, dir_fd: int, cap: int) -> bytes | None:
    """The file's first bytes if it is a regular file no larger than ``cap``."""
    try:
        fd = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK, dir_fd=dir_fd)
    except OSError:
        return None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or info.st_size > cap:
            return None
        return os.read(fd, cap)
    except OSError:
        return None
    finally:
        os.close(fd)


def sketch(files: dict[str, set[int]]) -> set[int]:
    """A submission's shingles: all of them, or the ``MAX_SHINGLES`` smallest."""
    found = set().union(*files.values()) if files else set()
    return found if len(found) <= MAX_SHINGLES else set(heapq.nsmallest(MAX_SHINGLES, found))


def near_identical_sources(sources: dict[str, dict[str, set[int]]]) -> list[Pair]:
    """Pairs whose shingles, less those most of the class shares, are mostly shared."""
    sets = {name: sketch(files) for name, files in sources.items()}
    common = max(3, math.ceil(len(sets) / 2))  # in this many submissions: the template's
    holders: dict[int, list[str]] = defaultdict(list)
    for name, found in sets.items():
        for shingle in found:
            holders[shingle].append(name)
    shared: Counter = Counter()
    size: Counter = Counter()
    dropped = set()
    for shingle, names in holders.items():
        if len(names) < common:
            size.update(names)
            shared.update(combinations(sorted(names), 2))
        else:
            dropped.add(shingle)
    pairs = []
    for (first, second), count in shared.items():
        union = size[first] + size[second] - count
        if count >= MIN_SHARED and count / union >= MIN_JACCARD:
            pairs.append(Pair(first, second, "near-identical sources",
                              f"{count} of their {union} distinct {SHINGLE}-token shingles "
                              f"shared ({count / union:.0%}); most alike: "
                              f"{_most_alike(sources[first], sources[second], dropped)}",
                              count / union))
    return pairs


def _most_alike(first: dict[str, set[int]], second: dict[str, set[int]],
                dropped: set[int]) -> str:
    """The two files, one of each, that share the most shingles (not the class's)."""
    def largest(files: dict[str, set[int]]) -> list[tuple[str, set[int]]]:
        return sorted(files.items(), key=lambda item: -len(item[1]))[:MOST_ALIKE_FILES]
    best = max(((len((a & b) - dropped), name_a, name_b) for name_a, a in largest(first)
                for name_b, b in largest(second)), default=(0, "", ""))
    return f"{best[1]} and {best[2]} ({best[0]} shingles)"

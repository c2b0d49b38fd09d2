"""A binary min-heap of :class:`HeapEntry` objects, ``heapq``'s own steps typed.

Compiled (mypyc), ``heapq`` is a generic call that compares tuples element by
element, and a typed tuple read from a list is unpacked and boxed again at every
move; these functions compare two fields natively. They make exactly the heaps
``heapq`` makes of the tuples ``(key, order)`` (a test holds them to it), so a
search that used ``heapq`` visits in the same order.
"""

from __future__ import annotations


class HeapEntry:
    """Ordered as the tuple ``(key, order)``; subclasses carry what is filed."""

    __slots__ = ("key", "order")

    def __init__(self, key: float, order: int) -> None:
        self.key = key
        self.order = order


def before(a: HeapEntry, b: HeapEntry) -> bool:
    """``(a.key, a.order) < (b.key, b.order)``."""
    return a.key < b.key or (a.key == b.key and a.order < b.order)


def heap_push(heap: list[HeapEntry], entry: HeapEntry) -> None:
    """``heapq.heappush``."""
    heap.append(entry)
    _sift_down(heap, 0, len(heap) - 1)


def heap_pop(heap: list[HeapEntry]) -> HeapEntry:
    """``heapq.heappop`` (IndexError on an empty heap)."""
    last = heap.pop()
    if not heap:
        return last
    top = heap[0]
    heap[0] = last
    _sift_up(heap, 0)
    return top


def heapify(heap: list[HeapEntry]) -> None:
    """``heapq.heapify``."""
    for pos in range(len(heap) // 2 - 1, -1, -1):
        _sift_up(heap, pos)


def _sift_down(heap: list[HeapEntry], start: int, pos: int) -> None:
    """heapq's ``_siftdown``: the entry at ``pos`` moves up past larger parents."""
    entry = heap[pos]
    while pos > start:
        parent_pos = (pos - 1) >> 1
        parent = heap[parent_pos]
        if not before(entry, parent):
            break
        heap[pos] = parent
        pos = parent_pos
    heap[pos] = entry


def _sift_up(heap: list[HeapEntry], pos: int) -> None:
    """heapq's ``_siftup``: the smaller child rises until a leaf, then the entry
    from ``pos`` sifts down there."""
    end, start, entry = len(heap), pos, heap[pos]
    child = 2 * pos + 1
    while child < end:
        right = child + 1
        if right < end and not before(heap[child], heap[right]):
            child = right
        heap[pos] = heap[child]
        pos = child
        child = 2 * pos + 1
    heap[pos] = entry
    _sift_down(heap, start, pos)

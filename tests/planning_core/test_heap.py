"""planning_core.heap makes heapq's heaps."""

import heapq
import random

from planning_core.heap import HeapEntry, heap_pop, heap_push, heapify


def as_tuples(heap):
    return [(entry.key, entry.order) for entry in heap]


def test_the_heap_is_heapqs():
    """The same lists as heapq's of (key, order) after every push, pop and heapify,
    keys often equal (the order decides)."""
    rng = random.Random(3)
    ours: list = []
    theirs: list = []
    for order in range(3000):
        if ours and rng.random() < 0.4:
            popped = heap_pop(ours)
            assert (popped.key, popped.order) == heapq.heappop(theirs)
        else:
            key = -float(rng.choice([0.5, 1.0, 2.0, rng.random()]))
            heap_push(ours, HeapEntry(key, order))
            heapq.heappush(theirs, (key, order))
        assert as_tuples(ours) == theirs
    shuffled = [HeapEntry(key, order) for key, order in theirs]
    rng.shuffle(shuffled)
    again = as_tuples(shuffled)
    heapify(shuffled)
    heapq.heapify(again)
    assert as_tuples(shuffled) == again
    while ours:
        heap_pop(ours)
        heapq.heappop(theirs)
        assert as_tuples(ours) == theirs

"""Worlds: where a system's body lives and what it may not touch.

``shapes`` holds exact closed-set geometry on floats (rects, discs, convex
polygons, segments); ``continuous`` the continuous world of SPEC section 5 (a
closed box and closed obstacles).
"""

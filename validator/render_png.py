"""The validator's picture as PNG: the PDF's pages (render_pdf) rasterised by pypdfium2
at 144 dots per inch and stacked, one under the other, in one image. The PNG is
written here (zlib), so Pillow is not needed; reportlab and pypdfium2 are.
"""

from __future__ import annotations

import io
import struct
import zlib
from typing import Sequence

import pypdfium2 as pdfium

from validator.render_file import write_atomically
from validator.render_pdf import render_pdf

SCALE = 2.0  # pixels a PDF point: 144 dots per inch


def _chunk(kind: bytes, data: bytes) -> bytes:
    return (struct.pack(">I", len(data)) + kind + data
            + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))


def png_bytes(width: int, rows: Sequence[bytes]) -> bytes:
    """An 8-bit RGB PNG of ``rows`` (``3 * width`` bytes each, top first)."""
    raw = b"".join(b"\x00" + row for row in rows)  # filter 0 (none) on every row
    header = struct.pack(">IIBBBBB", width, len(rows), 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header)
            + _chunk(b"IDAT", zlib.compress(raw, 6)) + _chunk(b"IEND", b""))


def _page_rows(page) -> tuple[int, list[bytes]]:
    bitmap = page.render(scale=SCALE, rev_byteorder=True)  # RGB(A) in byte order
    width, height, stride = bitmap.width, bitmap.height, bitmap.stride
    channels = 4 if bitmap.mode in ("RGBA", "RGBX") else 3
    buffer = bytes(bitmap.buffer)
    rows = []
    for y in range(height):
        row = bytearray(buffer[y * stride:y * stride + width * channels])
        if channels == 4:
            del row[3::4]  # RGBX or RGBA: the fourth byte of each pixel out
        rows.append(bytes(row))
    return width, rows


def pdf_to_png(pdf: bytes) -> bytes:
    """Every page of ``pdf``, one under the other on white, as one PNG."""
    document = pdfium.PdfDocument(pdf)
    pages = [_page_rows(document[k]) for k in range(len(document))]
    width = max(w for w, _ in pages)
    rows = [row + b"\xff" * (3 * (width - w)) for w, page_rows in pages for row in page_rows]
    return png_bytes(width, rows)


def render_png(path: str, problem, vehicle, report, verdict: str, notes: Sequence[str] = (),
               label: str = "") -> None:
    """Draw the PDF and write it to ``path`` as one PNG, whole or not at all."""
    pdf = io.BytesIO()
    render_pdf(pdf, problem, vehicle, report, verdict, notes, label)
    data = pdf_to_png(pdf.getvalue())
    write_atomically(path, lambda out: out.write(data))

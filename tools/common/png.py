"""Reading PNG files (8-bit, non-interlaced grey, grey+alpha, RGB or RGBA: what the programs write)."""

import contextlib
import struct
import zlib

SIGNATURE = b"\x89PNG\r\n\x1a\n"
_IEND = b"\x00\x00\x00\x00IEND\xaeB`\x82"
_CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}


class PngError(ValueError):
    pass


def size(data: bytes) -> tuple[int, int]:
    """(width, height) from the IHDR chunk; PngError when the file does not start as a PNG."""
    if not data.startswith(SIGNATURE):
        raise PngError(f"not a PNG (the first 8 bytes are {data[:8]!r}, not the PNG signature)")
    if len(data) < 33:
        raise PngError(f"truncated PNG ({len(data)} bytes, too short for an IHDR chunk)")
    length, chunk = struct.unpack(">I4s", data[8:16])
    if chunk != b"IHDR" or length != 13:
        raise PngError(f"the first PNG chunk is {chunk!r} of length {length}, expected IHDR of length 13")
    return struct.unpack(">II", data[16:24])


def size_of(path) -> tuple[int, int] | None:
    """(width, height) of a PNG file, or None if the file is not a PNG."""
    with open(path, "rb") as f, contextlib.suppress(PngError):
        return size(f.read(33))
    return None


def problems(data: bytes) -> list[str]:
    """What makes `data` a broken PNG: no signature or IHDR, a zero size, a bad CRC, no IEND."""
    try:
        width, height = size(data)
    except PngError as e:
        return [str(e)]
    found = [f"PNG has size {width}x{height}; both must be non-zero"] if not width or not height else []
    if zlib.crc32(data[12:29]) != struct.unpack(">I", data[29:33])[0]:
        found.append("the IHDR chunk's CRC does not match (corrupt file)")
    if not data.endswith(_IEND):
        found.append("PNG does not end with an IEND chunk (truncated: was it written atomically?)")
    return found


def decode(data: bytes) -> tuple[int, int, int, bytes]:
    """(width, height, channels, pixels), the rows' filters undone (PNG specification, section 9)."""
    width, height = size(data)
    depth, colour, interlace = data[24], data[25], data[28]
    channels = _CHANNELS.get(colour)
    if depth != 8 or channels is None or interlace:
        raise PngError(f"unsupported PNG (bit depth {depth}, colour type {colour}, interlace {interlace})")
    raw = zlib.decompress(b"".join(_chunks(data, b"IDAT")))
    stride = width * channels
    if len(raw) != height * (stride + 1):
        raise PngError("PNG data of the wrong length")
    pixels, previous = bytearray(), bytearray(stride)
    for y in range(height):
        previous = _unfilter(raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)]),
                             previous, channels, y)
        pixels += previous
    return width, height, channels, bytes(pixels)


def _chunks(data: bytes, wanted: bytes):
    pos = 8
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        if kind == b"IEND":
            return
        if kind == wanted:
            yield data[pos + 8:pos + 8 + length]
        pos += 12 + length


def _unfilter(kind: int, row: bytearray, previous: bytearray, channels: int, y: int) -> bytearray:
    if kind not in range(5):
        raise PngError(f"PNG row {y} has unknown filter {kind}")
    if kind in (0, 2):  # None, Up
        return row if kind == 0 else bytearray((a + b) & 255 for a, b in zip(row, previous))
    for i in range(len(row)):
        a = row[i - channels] if i >= channels else 0
        b = previous[i]
        if kind == 1:    # Sub
            row[i] = (row[i] + a) & 255
        elif kind == 3:  # Average
            row[i] = (row[i] + ((a + b) >> 1)) & 255
        else:            # Paeth
            c = previous[i - channels] if i >= channels else 0
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    return row

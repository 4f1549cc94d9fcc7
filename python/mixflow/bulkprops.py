"""constant/bulkProperties of a bulk-model case (prepare/BulkModel.cpp reads it; every entry and
its default: docs/parameters.md): where it is, its blocks read, and blocks written in place."""
import os

from .foamdict import DictError, parse_dict, set_block_text

FILE = os.path.join("constant", "bulkProperties")
HEADER = "FoamFile { version 2.0; format ascii; class dictionary; object bulkProperties; }\n"


def path(case):
    return os.path.join(case, FILE)


def read(case):
    """The parsed bulkProperties of CASE ({} when absent); DictError names the line."""
    p = path(case)
    if not os.path.exists(p):
        return {}
    with open(p) as f:
        return parse_dict(f.read())


def block_text(p, block, entries):
    """The text of the bulkProperties file P with BLOCK's ENTRIES (value strings) set, every other
    byte kept (a new file when absent); DictError for an unreadable file or BLOCK as an entry."""
    text = None
    if os.path.exists(p):
        with open(p) as f:
            text = f.read()
    return set_block_text(text, block, entries, HEADER)


def write_text(p, text):
    """TEXT into P through a temporary file renamed over it: an interrupted write keeps the old."""
    with open(p + ".tmp", "w") as f:
        f.write(text)
    os.replace(p + ".tmp", p)


__all__ = ["DictError", "FILE", "HEADER", "block_text", "path", "read", "write_text"]

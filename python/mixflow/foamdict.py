"""OpenFOAM-style dictionaries: the reader and the editor of every Python tool.

parse_dict / read_dict give nested dicts of value strings; edit_dict sets entries in a text and
changes only the values it sets (comments, layout and every other entry stay as they are);
edit_file does the same to a file; format_dict writes a nested dict as dictionary text.
"""


class DictError(Exception):
    """A dictionary that cannot be read or an override that cannot be applied."""


# A reader that keeps positions, so that an edit changes only the value it sets.

def _tokens(text):
    """(kind, start, end) with kind one of word, string, { } ; ( ); comments skipped."""
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c.isspace():
            i += 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j + 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            if j < 0:
                raise DictError(f"unterminated /* comment at character {i}")
            i = j + 2
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            if j >= n:
                raise DictError(f"unterminated string at character {i}")
            yield "string", i, j + 1
            i = j + 1
        elif c in "{};()":
            yield c, i, i + 1
            i += 1
        else:
            j = i
            while j < n and not text[j].isspace() and text[j] not in '{};()"' \
                    and not text.startswith("//", j) and not text.startswith("/*", j):
                j += 1
            yield "word", i, j
            i = j


class _Entry:
    def __init__(self, key, key_start, value_start, value_end):
        self.key, self.key_start, self.value_start, self.value_end = key, key_start, value_start, value_end


class _Block:
    def __init__(self, key, key_start, open_pos):
        self.key, self.key_start, self.open, self.close = key, key_start, open_pos, None
        self.children = {}


def _parse(text):
    """The tree of blocks and entries of TEXT with their positions (the root's close = len)."""
    toks = list(_tokens(text))
    root = _Block("", 0, -1)
    stack = [root]
    i = 0
    while i < len(toks):
        kind, s, e = toks[i]
        if kind == "}":
            if len(stack) == 1:
                raise DictError(f"unmatched '}}' on line {text.count(chr(10), 0, s) + 1}")
            stack.pop().close = s
            i += 1
            continue
        if kind not in ("word", "string"):
            raise DictError(f"expected a keyword, found '{text[s:e]}' on line "
                            f"{text.count(chr(10), 0, s) + 1}")
        key = text[s:e]
        if key.startswith("#"):  # directive (#include ...): to the end of its line
            eol = text.find("\n", s)
            eol = len(text) if eol < 0 else eol
            while i < len(toks) and toks[i][1] < eol:
                i += 1
            continue
        if i + 1 < len(toks) and toks[i + 1][0] == "{":
            blk = _Block(key, s, toks[i + 1][1])
            stack[-1].children[key] = blk
            stack.append(blk)
            i += 2
            continue
        j, depth = i + 1, 0
        while j < len(toks) and not (toks[j][0] == ";" and depth == 0):
            if toks[j][0] == "(":
                depth += 1
            elif toks[j][0] == ")":
                depth -= 1
            elif toks[j][0] in "{}":
                raise DictError(f"entry '{key}' on line {text.count(chr(10), 0, s) + 1} has no ';'")
            j += 1
        if j >= len(toks):
            raise DictError(f"entry '{key}' on line {text.count(chr(10), 0, s) + 1} has no ';'")
        vs = toks[i + 1][1] if j > i + 1 else toks[j][1]
        stack[-1].children[key] = _Entry(key, s, vs, toks[j][1])
        i = j + 1
    if len(stack) > 1:
        raise DictError(f"block '{stack[-1].key}' is not closed")
    root.close = len(text)
    return root


def _to_python(text, blk):
    return {k: _to_python(text, c) if isinstance(c, _Block) else text[c.value_start:c.value_end].strip()
            for k, c in blk.children.items()}


def parse_dict(text):
    """Nested dict of an OpenFOAM-style dictionary: blocks -> dicts, entries -> value strings."""
    return _to_python(text, _parse(text))


def read_dict(path):
    try:
        with open(path) as f:
            return parse_dict(f.read())
    except DictError as e:
        raise DictError(f"{path}: {e}") from None


def list_value(value):
    """'(a b c)' -> ['a', 'b', 'c']."""
    return value.strip().strip("()").split()


def unquote(value):
    v = value.strip()
    return v[1:-1] if len(v) >= 2 and v[0] == v[-1] == '"' else v


def leaves(tree, prefix=()):
    """(path tuple, value) of every entry of a nested dict, depth first."""
    for k, v in tree.items():
        if isinstance(v, dict):
            yield from leaves(v, prefix + (k,))
        else:
            yield prefix + (k,), v


def _insertion(text, blk, line, comment=""):
    """(position, text) that adds LINE (a statement, no newline) as the last one of block BLK."""
    close = blk.close
    line_start = text.rfind("\n", 0, close) + 1
    if blk.open < 0:  # the file itself
        return close, f"{'' if text.endswith(chr(10)) or not text else chr(10)}{line}{comment}\n"
    if text[line_start:close].strip() == "":  # '}' alone on its line: indent one more
        return line_start, f"{text[line_start:close]}    {line}{comment}\n"
    return close, f"{line} "  # one-line block: before the '}'


def add_missing_blocks(text, overrides):
    """TEXT with an empty block added for every block of OVERRIDES it lacks."""
    for path, _ in leaves(overrides):
        for depth in range(len(path) - 1):
            blk = _parse(text)
            for name in path[:depth]:
                blk = blk.children[name]
            if path[depth] not in blk.children:
                pos, add = _insertion(text, blk, f"{path[depth]} {{ }}")
                text = text[:pos] + add + text[pos:]
    return text


def edit_dict(text, overrides, note="", optional=lambda path: False, create_blocks=False):
    """Sets every leaf of OVERRIDES (nested dict of value strings) in TEXT.

    An entry that exists gets the new value (a comment on the rest of its line becomes
    `// NOTE (case: OLD)` when the value changes); an absent entry is inserted at the end of its
    block. A block that does not exist is an error (DictError naming the dotted path), unless
    optional(path of the block) is true: then that override is skipped; with CREATE_BLOCKS it is
    inserted instead.
    Returns (new text, [(dotted key, value, action)]) with action set, kept, inserted or skipped.
    """
    if create_blocks:
        text = add_missing_blocks(text, overrides)
    root = _parse(text)
    edits, actions = [], []
    for path, value in leaves(overrides):
        blk, missing = root, None
        for depth, name in enumerate(path[:-1]):
            child = blk.children.get(name)
            if isinstance(child, _Entry):
                raise DictError(f"'{'.'.join(path[:depth + 1])}' is an entry, not a block")
            if child is None:
                missing = path[:depth + 1]
                break
            blk = child
        dotted = ".".join(path)
        if missing:
            if optional(missing):
                actions.append((dotted, value, "skipped"))
                continue
            raise DictError(f"no block '{'.'.join(missing)}' for '{dotted}'")
        key = path[-1]
        cur = blk.children.get(key)
        if isinstance(cur, _Block):
            raise DictError(f"'{dotted}' is a block, not an entry")
        if cur is not None:
            old = text[cur.value_start:cur.value_end].strip()
            if old == value:
                actions.append((dotted, value, "kept"))
                continue
            end = cur.value_end + 1
            eol = text.find("\n", end)
            eol = len(text) if eol < 0 else eol
            rest = text[end:eol]
            if note and rest.strip().startswith("//"):
                pad = rest[:len(rest) - len(rest.lstrip())] or "   "
                edits.append((end, eol, f"{pad}// {note} (case: {old})"))
            edits.append((cur.value_start, cur.value_end, value))
            actions.append((dotted, value, "set"))
            continue
        pos, add = _insertion(text, blk, f"{key} {value};", f"   // {note}" if note else "")
        edits.append((pos, pos, add))
        actions.append((dotted, value, "inserted"))
    # Apply back to front; inserts at one position keep the order they were made in.
    for _, (s, e, rep) in sorted(enumerate(edits), key=lambda x: (x[1][0], x[0]), reverse=True):
        text = text[:s] + rep + text[e:]
    return text, actions


def format_dict(tree, indent=0):
    """Nested dict of strings -> dictionary text."""
    pad = " " * indent
    out = []
    for k, v in tree.items():
        if isinstance(v, dict):
            out.append(f"{pad}{k}\n{pad}{{\n{format_dict(v, indent + 4)}{pad}}}\n")
        else:
            out.append(f"{pad}{k} {v};\n")
    return "".join(out)


def set_block_text(text, block, entries, header):
    """TEXT (None: a new file starting with HEADER) with the entries of BLOCK (a dict of value
    strings) set through edit_dict; a missing BLOCK is appended, every other byte stays."""
    if text is None:
        return header + format_dict({block: entries})
    tree = parse_dict(text)  # DictError names the line
    if block in tree and not isinstance(tree[block], dict):
        raise DictError(f"'{block}' is an entry, not a block")
    if block not in tree:
        return text + ("" if text.endswith("\n") or not text else "\n") + \
            format_dict({block: entries})
    return edit_dict(text, {block: entries})[0]


def edit_file(path, overrides, **options):
    """edit_dict on the file PATH, written back; returns edit_dict's actions."""
    with open(path) as f:
        text = f.read()
    text, actions = edit_dict(text, overrides, **options)
    with open(path, "w") as f:
        f.write(text)
    return actions

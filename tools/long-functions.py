#!/usr/bin/env python3
"""Lists the functions longer than N lines (default 120) in the workspace's Rust sources,
tests left out: files under tests/ and benches/, and `#[cfg(test)]` modules."""
import os, re, sys
limit = int(sys.argv[1]) if len(sys.argv) > 1 else 120
root = sys.argv[2] if len(sys.argv) > 2 else '.'
fn_re = re.compile(r'^\s*(pub(\([a-z]+\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?fn\s+([A-Za-z_0-9]+)')
def strip(line):
    # drop strings, chars and comments crudely for brace counting
    line = re.sub(r'//.*', '', line)
    line = re.sub(r'"(\\.|[^"\\])*"', '""', line)
    line = re.sub(r"'(\\.|[^'\\])'", "' '", line)
    return line
out = []
for dp, dn, fn in os.walk(root):
    dn[:] = [d for d in dn if d not in ('target', '.git', 'tests', 'benches', 'node_modules')]
    for f in fn:
        if not f.endswith('.rs') or f.endswith('tests.rs') or f.startswith('test_'):
            continue
        p = os.path.join(dp, f)
        lines = open(p, encoding='utf-8', errors='replace').read().split('\n')
        i = 0
        skip_depth = None
        depth = 0
        pending_cfg_test = False
        stack = []  # (name, start_line, depth_at_open)
        for n, raw in enumerate(lines, 1):
            line = strip(raw)
            if re.match(r'\s*#\[cfg\(test\)\]', raw):
                pending_cfg_test = True
                continue
            m = fn_re.match(line)
            opens = line.count('{'); closes = line.count('}')
            if pending_cfg_test and re.match(r'\s*(pub(\([a-z]+\))?\s+)?mod\s', line):
                if skip_depth is None:
                    skip_depth = depth
            if not raw.strip().startswith('#'):
                pending_cfg_test = False if raw.strip() else pending_cfg_test
            if m and skip_depth is None:
                stack.append([m.group(6), n, depth, False])
            depth += opens - closes
            # mark fn body opened
            for s in stack:
                if not s[3] and depth > s[2]:
                    s[3] = True
            while stack and stack[-1][3] and depth <= stack[-1][2]:
                name, start, _, _ = stack.pop()
                length = n - start + 1
                if length > limit:
                    out.append((length, p, start, name))
            # fn declarations without body (trait) : drop if ';' at depth same
            if stack and not stack[-1][3] and line.rstrip().endswith(';'):
                stack.pop()
            if skip_depth is not None and depth <= skip_depth and closes:
                skip_depth = None
for length, p, start, name in sorted(out, reverse=True):
    print(f'{length:5d}  {p}:{start}  {name}')
print(f'{len(out)} functions over {limit} lines')

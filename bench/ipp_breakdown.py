#!/usr/bin/env python3
"""Where the instructions of one public call go, by header function.

usage: python3 bench/ipp_breakdown.py BINARY CASE FUNCTION [TOP]
  BINARY    a bench/ipp.c build with -g (make build/ipp-sse2 build/ipp-avx2)
  CASE      one of bench/ipp.c's cases (easy, slant, hard, two-eyes, ...)
  FUNCTION  sbl_temporal_filter or sbl_stereo_blend
  TOP       how many rows to print (default 30)

Runs callgrind with --dump-instr=yes inside FUNCTION only (as bench/ipp.sh counts), then
maps every instruction address through addr2line's inline chain to the innermost
function of stereoblend.h that is not a SIMD-layer wrapper (sbl__add, sbl__load, ...):
the kernel is inlined into a few large functions, and callgrind's own per-function
figures would put nearly everything there. Prints instructions per pixel (640x360,
per call as bench/ipp.sh divides) per function. Needs valgrind and binutils' addr2line.
"""
import collections
import os
import re
import subprocess
import sys
import tempfile

PIXELS = 640 * 360
# the SIMD layer's one-line wrappers: their instructions are charged to the caller
WRAPPER = re.compile(r'^(sbl__(add|sub|mul|div|min|max|sel|set1|load|loadu|store|storeu|gt|ge|lt|le|eq|'
                     r'and|or|andnot|not|abs|sqrt|all|any|floor|m[a-z]{0,6}|d[a-z]{0,6}|i[a-z]{0,6}|'
                     r'cvt\w*|bits\w*)|_mm\w*)$')


def costs_by_address(path):
    """Ir per instruction address from a callgrind file written with --dump-instr=yes
    (positions: instr line; a call's inclusive cost line is skipped)."""
    cost = collections.Counter()
    last = [0, 0]
    after_calls = False
    with open(path) as f:
        for raw in f:
            raw = raw.rstrip('\n')
            if raw.startswith('calls='):
                after_calls = True
                continue
            if not raw or not (raw[0].isdigit() or raw[0] in '+-*'):
                continue
            parts = raw.split()
            pos = []
            for j, p in enumerate(parts[:2]):
                if p == '*':
                    v = last[j]
                elif p[0] == '+':
                    v = last[j] + int(p[1:], 0)
                elif p[0] == '-':
                    v = last[j] - int(p[1:], 0)
                else:
                    v = int(p, 0)
                pos.append(v)
            last = pos[:]
            c = int(parts[2]) if len(parts) > 2 else 0
            if after_calls:
                after_calls = False
                continue
            cost[pos[0]] += c
    return cost


def inline_chains(binary, addrs):
    out = subprocess.run(['addr2line', '-e', binary, '-i', '-f', '-a'] + ['%x' % a for a in addrs],
                         capture_output=True, text=True, check=True).stdout.split('\n')
    chains, cur = {}, None
    for line in out:
        if line.startswith('0x'):
            cur = int(line, 16)
            chains[cur] = []
        elif cur is not None and line:
            chains[cur].append(line)
    return chains


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    binary, case, function = sys.argv[1:4]
    top = int(sys.argv[4]) if len(sys.argv) > 4 else 30
    calls = 2 if function == 'sbl_temporal_filter' or case == 'two-eyes' else 1
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, 'cg.out')
        subprocess.run(['valgrind', '--tool=callgrind', '--toggle-collect=' + function, '--dump-instr=yes',
                        '--callgrind-out-file=' + out, binary, case],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        cost = costs_by_address(out)
    chains = inline_chains(binary, sorted(cost))
    by_fn = collections.Counter()
    for addr, chain in chains.items():
        names = chain[0::2]  # (function, file:line) pairs, innermost first
        picked = next((n for n in names if n.startswith('sbl') and not WRAPPER.match(n)), '(outside the header)')
        by_fn[picked] += cost[addr]
    total = sum(cost.values())
    px = float(PIXELS * calls)
    print('%s %s %s: %.1f instructions per pixel' % (os.path.basename(binary), case, function, total / px))
    for name, c in by_fn.most_common(top):
        print('%8.1f  %s' % (c / px, name))


if __name__ == '__main__':
    main()

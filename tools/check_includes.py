#!/usr/bin/env python3
"""Check that every file of src/<module>/ (and of tests/<module>/) includes only headers of the
modules that module may use: itself and, transitively, the modules it links in
cmake/modules.cmake (the order of docs/architecture.md). Usage: check_includes.py [ROOT].
Prints one line per offending include and exits 1 when there is any."""
import re, sys, pathlib
root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else '.')
text = (root / 'cmake/modules.cmake').read_text()
deps = {}
# a module whose DIRS are other folders (output/particles) owns the files there
owner = {}
for m in re.finditer(r'gs_module\((\w+)(.*?)\)', text, re.S):
    deps[m.group(1)] = re.findall(r'gs_(\w+)', m.group(2).split('DEPS', 1)[-1])
    dirs = re.search(r'DIRS\s+(.*?)(?:DEPS|$)', m.group(2), re.S)
    for d in (dirs.group(1).split() if dirs else []):
        owner.setdefault(tuple(d.split('/')), m.group(1))
for extra in re.finditer(r'target_link_libraries\(gs_(\w+) PUBLIC ((?:gs_\w+\s*)+)', text):
    deps.setdefault(extra.group(1), []).extend(re.findall(r'gs_(\w+)', extra.group(2)))
def closure(m, seen=None):
    seen = seen if seen is not None else set()
    if m in seen: return seen
    seen.add(m)
    for d in deps.get(m, []):
        closure({'render_gl': 'render', 'movie': 'output'}.get(d, d), seen)
    return seen
# a module's tests may include what their executable links (tests/CMakeLists.txt)
tests_text = (root / 'tests/CMakeLists.txt').read_text()
variables = {m.group(1): m.group(2) for m in re.finditer(r'set\((\w+)\s+([^)]*)\)', tests_text)}
test_deps = {}
for m in re.finditer(r'gs_test\((\w+)\s+DEPS\s+([^)\n]*)', tests_text):
    words = re.sub(r'\$\{(\w+)\}', lambda v: variables.get(v.group(1), ''), m.group(2))
    test_deps[m.group(1)] = re.findall(r'gs_(\w+)', words.split('#')[0])
def allowed_for(top, mod):
    if top == 'src' or mod not in test_deps: return closure(mod)
    out = {mod}
    for d in test_deps[mod]:
        out |= closure({'render_gl': 'render', 'movie': 'output'}.get(d, d))
    return out
bad = 0
files = [(f, 'src') for f in sorted((root / 'src').rglob('*'))]
files += [(f, 'tests') for f in sorted((root / 'tests').rglob('*'))]
for f, top in files:
    if f.suffix not in ('.cpp', '.hpp'): continue
    rel = f.relative_to(root / top)
    if len(rel.parts) < 2 or rel.parts[0] not in deps: continue
    mod = owner.get(tuple(rel.parts[:2]), rel.parts[0]) if top == 'src' else rel.parts[0]
    allowed = allowed_for(top, mod)
    for n, line in enumerate(f.read_text().splitlines(), 1):
        m = re.match(r'\s*#\s*include\s+"(\w+)/', line)
        if m and m.group(1) in deps and m.group(1) not in allowed:
            print(f'{top}/{rel}:{n}: {mod} includes {m.group(1)}/ (allowed: {", ".join(sorted(allowed - {mod}))})')
            bad += 1
sys.exit(1 if bad else 0)

#!/usr/bin/env python3
"""The mutation audit: every mutation of the lists beside this script is put behind
an environment switch in a copy of the repository (`(if crate::mutant::on(ID) {
MUTATED } else { ORIGINAL })`), the copy is built once, and for each mutant the test
suite's modules run one by one (goldens, the contact sheet, the README examples, the gallery, viewer
and installer tests left out: they pin outputs or test tools, not methods), the one
named after the mutated module first, then those of its folder, then the fastest, stopping at the first that
fails. Proptests run with a fixed seed and no persisted failures, so that one
mutant's failing case does not fail the next.

    python3 tools/mutation-audit/audit.py prepare   # copy and instrument
    python3 tools/mutation-audit/audit.py           # build, baseline, every mutant
    python3 tools/mutation-audit/audit.py report    # the table (docs/mutation-audit.md)

MUTATION_WORK (default /tmp/lumiere-mutants) holds the copy, its build and the
results; a run resumes where it stopped.

A list entry: a line `=== path | kind | what the mutation does`, then `<<<`, the
original expression (exactly once in the file), `---`, the mutated one, `>>>`. Three
per module: a sign, a constant, an off-by-one, each a plausible slip in the method's
own arithmetic."""
import json, os, re, subprocess, sys, time, glob

HERE = os.path.dirname(os.path.abspath(__file__))
MAIN = os.path.dirname(os.path.dirname(HERE))
BASE = os.environ.get('MUTATION_WORK', '/tmp/lumiere-mutants')
WORK = os.path.join(BASE, 'repository')
TARGET = os.path.join(BASE, 'target')
ENTRIES = os.path.join(BASE, 'entries.json')
RESULTS = os.path.join(BASE, 'results.json')
EXCLUDE = {'golden', 'cli::contact_sheet', 'project::readme_examples', 'cli::gallery', 'viewer',
           'project::installers', 'project::layers'}

def parse(path):
    entries, cur, mode, orig, mut = [], None, None, [], []
    for line in open(path):
        line = line.rstrip('\n')
        if mode is None and line.startswith('=== '):
            f, kind, desc = [x.strip() for x in line[4:].split('|', 2)]
            cur = dict(file=f, kind=kind, desc=desc); orig, mut = [], []
        elif line == '<<<' and cur: mode = 'orig'
        elif line == '---' and mode == 'orig': mode = 'mut'
        elif line == '>>>' and mode == 'mut':
            cur['orig'] = '\n'.join(orig); cur['mut'] = '\n'.join(mut)
            entries.append(cur); cur, mode = None, None
        elif mode == 'orig': orig.append(line)
        elif mode == 'mut': mut.append(line)
    return entries

def prepare():
    entries = []
    for f in sorted(glob.glob(os.path.join(HERE, '*.txt'))):
        entries += parse(f)
    os.makedirs(BASE, exist_ok=True)
    subprocess.run(['rm', '-rf', WORK], check=True)
    subprocess.run(['git', 'clone', '-q', MAIN, WORK], check=True)
    applied = []
    for i, e in enumerate(entries, 1):
        e['id'] = i
        p = os.path.join(WORK, e['file'])
        s = open(p).read()
        if s.count(e['orig']) != 1:
            e['status'] = 'not applied (snippet count %d)' % s.count(e['orig'])
            continue
        s = s.replace(e['orig'], '(if crate::mutant::on(%d) { %s } else { %s })' % (i, e['mut'], e['orig']))
        open(p, 'w').write(s)
        applied.append(e)
    open(os.path.join(WORK, 'src/mutant.rs'), 'w').write(
        '//! Mutation audit switch.\n'
        'pub fn on(id: u32) -> bool {\n'
        '    static M: std::sync::OnceLock<u32> = std::sync::OnceLock::new();\n'
        '    *M.get_or_init(|| std::env::var("LUMIERE_MUTANT").ok().and_then(|v| v.parse().ok()).unwrap_or(0)) == id\n'
        '}\n')
    lib = open(os.path.join(WORK, 'src/lib.rs')).read()
    open(os.path.join(WORK, 'src/lib.rs'), 'w').write(lib + '\n#[doc(hidden)]\npub mod mutant;\n')
    json.dump(entries, open(ENTRIES, 'w'), indent=1)
    return entries

def build():
    env = dict(os.environ, CARGO_TARGET_DIR=TARGET)
    r = subprocess.run(['cargo', 'test', '--release', '--no-run', '--message-format=json'],
                       cwd=WORK, env=env, capture_output=True, text=True)
    bins = []
    for line in r.stdout.splitlines():
        try: m = json.loads(line)
        except ValueError: continue
        if m.get('reason') == 'compiler-message' and m['message']['level'] == 'error':
            print(m['message']['rendered'], file=sys.stderr)
        if m.get('reason') == 'compiler-artifact' and m.get('executable') and m['profile']['test']:
            name = m['target']['name']
            if m['target']['kind'] == ['lib']: name = 'unittests'
            if m['target']['kind'] == ['bin']: name = 'bin-unittests'
            bins.append((name, m['executable']))
    if r.returncode != 0:
        print(r.stderr[-5000:], file=sys.stderr); sys.exit(1)
    # The suite is one binary; its modules (shadow::hard, radiosity::solutions, ...)
    # are run one at a time by their path, as the test binaries once were.
    groups = []
    for n, b in bins:
        if n != 'suite':
            groups.append((n, b, []))
            continue
        listed = subprocess.run([b, '--list', '--format', 'terse'], cwd=WORK, capture_output=True, text=True).stdout
        paths = [l.rsplit(': ', 1)[0] for l in listed.splitlines() if l.endswith(': test')]
        by_group = {}
        for path in paths:
            parts = path.split('::')
            by_group.setdefault('::'.join(parts[:2]) if len(parts) > 2 else parts[0], []).append(path)
        for g, members in sorted(by_group.items()):
            groups.append((g, b, ['--exact', *members]))
    excluded = lambda n: n in EXCLUDE or n.split('::')[0] in EXCLUDE
    return [g for g in groups if not excluded(g[0])]

def run(binary, mutant, timeout=300, filters=()):
    env = dict(os.environ, LUMIERE_MUTANT=str(mutant), RUST_BACKTRACE='0', PROPTEST_CASES='24', PROPTEST_DISABLE_FAILURE_PERSISTENCE='1', PROPTEST_RNG_SEED='7')
    t = time.time()
    try:
        r = subprocess.run([binary, '--test-threads', '2', *filters], cwd=WORK, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return 'timeout', [], time.time() - t
    failed = re.findall(r'^test (\S+) \.\.\. FAILED', r.stdout, re.M)
    if r.returncode == 0: return 'pass', [], time.time() - t
    return 'fail', failed or ['(crash: %s)' % (r.stderr.strip().splitlines() or ['?'])[-1][:200]], time.time() - t

def report():
    entries = {e['id']: e for e in json.load(open(ENTRIES))}
    results = json.load(open(RESULTS))
    rows = []
    for key, v in sorted(((k, v) for k, v in results.items() if k != '0'), key=lambda kv: int(kv[0])):
        e = entries[int(key)]
        verdict = 'caught by `%s` (%s)' % (v['caught_by'], ', '.join('`%s`' % t.split('::')[-1] for t in v['tests'][:2])) if v['status'] != 'survived' else '**survived**'
        rows.append('| %s | `%s` | %s | %s | %s |' % (key, e['file'], e['kind'], e['desc'].replace('|', '/'), verdict))
    print('| # | module | kind | mutation | verdict |')
    print('|---|---|---|---|---|')
    print('\n'.join(rows))

def main():
    if sys.argv[1:] == ['report']:
        report(); return
    if sys.argv[1:] == ['prepare']:
        entries = prepare(); print(len(entries), 'entries', sum('status' not in e for e in entries), 'applied'); return
    entries = json.load(open(ENTRIES))
    bins = build()
    results_path = RESULTS
    results = json.load(open(results_path)) if os.path.exists(results_path) else {}
    times = {}
    if '0' not in results:
        base = {}
        for n, b, f in bins:
            st, failed, dt = run(b, 0, filters=f)
            times[n] = dt; base[n] = (st, failed)
            print('baseline', n, st, failed, '%.1fs' % dt, flush=True)
        results['0'] = dict(base=base, times=times)
        json.dump(results, open(results_path, 'w'), indent=1)
    times = results['0']['times']
    bad = [n for n, (st, _) in results['0']['base'].items() if st != 'pass']
    if bad: print('baseline failures', bad); bins = [g for g in bins if g[0] not in bad]
    bins.sort(key=lambda nb: times.get(nb[0], 99))
    only = set(sys.argv[1:])
    for e in entries:
        key = str(e['id'])
        if 'status' in e or key in results or (only and key not in only): continue
        stem = os.path.splitext(os.path.basename(e['file']))[0]
        folder = e['file'].split('/')[1]
        def prio(group):
            n = group[0]
            return (0 if stem in n or n.split('::')[-1] in stem else 1 if n.split('::')[0] == folder else 2, times.get(n, 99))
        verdict = dict(file=e['file'], kind=e['kind'], desc=e['desc'], caught_by=None, tests=[], status='survived')
        t0 = time.time()
        for n, b, f in sorted(bins, key=prio):
            st, failed, dt = run(b, e['id'], filters=f)
            if st != 'pass':
                verdict.update(caught_by=n, tests=failed[:5], status='caught' if st == 'fail' else 'timeout')
                break
        verdict['seconds'] = round(time.time() - t0, 1)
        results[key] = verdict
        json.dump(results, open(results_path, 'w'), indent=1)
        print(e['id'], e['file'], e['kind'], verdict['status'], verdict['caught_by'], verdict['tests'][:2], verdict['seconds'], flush=True)

main()

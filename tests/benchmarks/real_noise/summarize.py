import json, sys, re, os
def fmt(v):
    return '%.3g' % v if v is not None else '-'
for d in sys.argv[1:]:
    j = json.load(open(d + '/results.json')); s = j['stages'][-1]
    log = os.path.join(os.path.dirname(d), 'run_' + os.path.basename(d)[4:] + '.log')
    wall = re.findall(r'WALL ([\d.]+)', open(log).read()) if os.path.exists(log) else []
    dist = s.get('disturbance') or {}
    chosen = [c['name'] for c in dist.get('candidates', []) if c.get('chosen')]
    print('=' * 100)
    print(d, '| method', dist.get('method', 'output_error'), '| chosen', chosen, '| verdict', j['verdict'], '| wall', wall, '| time_s', round(j['time_seconds'], 2))
    print('  uncertainty', s['uncertainty'].get('method'), s['uncertainty'].get('method_reason'))
    print('  params:', '; '.join('%s %s ± %s%s' % (p['name'], fmt(p['value']), fmt(p.get('std_error')), ' [%s]' % p['role'] if p['role'] != 'free' else '') for p in j['parameters']))
    ie = [e for e in s['estimates'] if e['name'].startswith(('x0', 'init', 'psi', 'r', 'eta'))]
    if ie: print('  init/other est:', '; '.join('%s %s ± %s' % (e['name'], fmt(e['value']), fmt(e.get('std_error'))) for e in ie)[:600])
    if dist.get('model'): print('  model:', dist['model'])
    for c in dist.get('candidates', []): print('   cand %-32s bic %12.1f k %2d nll %12.1f solved %s%s' % (c['name'], c['bic'], c['unknowns'], c['negative_log_likelihood'], c['solved'], ' CHOSEN' if c['chosen'] else ''))
    print('  train fit:', [(m['experiment'], m['output'], round(m['fit_percent'], 1)) for m in s['fit']['metrics']])
    print('  stage validation free-run:', [(m['experiment'], m['output'], round(m['fit_percent'], 1)) for m in (s.get('validation') or {}).get('metrics', [])])
    print('  final_validation free-run:', [(m['experiment'], m['output'], round(m['fit_percent'], 1)) for m in (j.get('final_validation') or {}).get('metrics', [])])
    for p in dist.get('predictions', []):
        print('   pred %-8s %-4s k=%d (%.2f s) k-step %.1f one-step %.1f free %.1f' % (p['experiment'], p['output'], p['steps'], p['seconds_ahead'], p['k_step_fit_percent'], p['one_step_fit_percent'], p['free_run_fit_percent']))
    for n in s['notes']:
        if re.search('innovation structure|output error.s estimates|moves|noise auto: output', n): print('   NOTE', n)
    fs = [(f['severity'], f['kind']) for f in s['findings'] + j['findings'] if f['severity'] in ('warning', 'failure')]
    print('  findings w/f:', sorted(set(fs)))
    for f in s['findings'] + j['findings']:
        if f['kind'] in ('disturbance_absorbs_structure',): print('   ABS', f['message'][:260])

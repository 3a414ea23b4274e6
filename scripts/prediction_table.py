#!/usr/bin/env python3
"""The prediction suite's table: one row per run directory, from its compare/metrics.json.

    scripts/prediction_table.py RUNDIR [RUNDIR ...] [--markdown FILE] [--json FILE]

Columns: case, Ra, the particle's Nu +- error, the nominal twin's Nu +- error, their gap, the
temperature, velocity and density L2 over their noise, the wall jumps (% of dT), and the verdict
of the fixed prediction tolerances (compare's "prediction" block: Nu within 2 combined errors +
2%, temperature L2 <= 1.5 noise or <= 1% of dT, velocity L2 <= 1.5 noise, density L2 <= 2 noise),
each failed tolerance named; compare's strict verdict beside it. Exit code 0; 2 when a directory
has no metrics.json (nothing written).
"""
import argparse
import json
import math
import os
import sys


def number(value):
    return float('nan') if value is None else float(value)


def row_of(run_dir):
    with open(os.path.join(run_dir, 'compare', 'metrics.json')) as f:
        m = json.load(f)
    t = m['table_row']
    nominal = m['twins']['nominal']
    prediction = m.get('prediction', {})
    jumps = m.get('particle', {}).get('wall_temperature_jumps', {})
    scale = number(m.get('temperature_scale'))
    failed = [k for k in ('nusselt', 'temperature', 'velocity', 'density')
              if k in prediction and not prediction[k]['pass']]

    def over(key):
        d = nominal.get(key)
        return number(d['l2']) / number(d['noise']) if d else float('nan')

    return {
        'case': m['case'],
        'run': run_dir,
        'rayleigh': number(t.get('rayleigh_nominal')),
        'nu_particle': number(t.get('nusselt_particle')),
        'nu_particle_stderr': number(t.get('nusselt_particle_stderr')),
        'nu_twin': number(t.get('nusselt_nominal')),
        'nu_twin_stderr': number(t.get('nusselt_nominal_stderr')),
        'gap': number(t.get('nusselt_particle')) / number(t.get('nusselt_nominal')) - 1,
        'temperature_over_noise': over('temperature'),
        'temperature_l2': number(nominal['temperature']['l2']) if 'temperature' in nominal else float('nan'),
        'velocity_over_noise': over('velocity'),
        'density_over_noise': over('density'),
        'jumps_percent': {k: 100 * number(v['jump']) / scale for k, v in jumps.items()},
        'prediction_pass': bool(prediction.get('pass', False)),
        'failed': failed,
        'strict_verdict': m['verdict'][0] if m.get('verdict') else '',
    }


def fmt(x, digits=3):
    return 'n/a' if x is None or (isinstance(x, float) and math.isnan(x)) else f'{x:.{digits}g}'


def markdown(rows):
    head = ('| case | Ra | Nu particle | Nu twin | gap | T L2 / noise | v L2 / noise | n L2 / noise '
            '| wall jumps (% dT) | prediction | compare (strict) |')
    lines = [head, '|' + '---|' * 11]
    for r in rows:
        jumps = ', '.join(f'{k} {v:+.1f}' for k, v in sorted(r['jumps_percent'].items()))
        verdict = 'pass' if r['prediction_pass'] else 'FAIL (' + ', '.join(r['failed']) + ')'
        strict = 'within errors' if 'matches' in r['strict_verdict'].split(';')[0] else 'beyond errors'
        lines.append(
            f"| {r['case']} | {fmt(r['rayleigh'])} | {r['nu_particle']:.4f} +- "
            f"{fmt(r['nu_particle_stderr'], 2)} | {r['nu_twin']:.4f} +- {fmt(r['nu_twin_stderr'], 2)} "
            f"| {100 * r['gap']:+.1f}% | {fmt(r['temperature_over_noise'])} "
            f"({fmt(r['temperature_l2'], 2)} dT) | {fmt(r['velocity_over_noise'])} "
            f"| {fmt(r['density_over_noise'])} | {jumps} | {verdict} | {strict} |")
    passed = sum(r['prediction_pass'] for r in rows)
    lines.append('')
    lines.append(f'{passed} of {len(rows)} cases meet every prediction tolerance.')
    return '\n'.join(lines) + '\n'


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('runs', nargs='+')
    parser.add_argument('--markdown')
    parser.add_argument('--json')
    args = parser.parse_args()
    for d in args.runs:
        if not os.path.isfile(os.path.join(d, 'compare', 'metrics.json')):
            print(f'prediction_table: {d}/compare/metrics.json: missing (twinflow run CASE --out {d})',
                  file=sys.stderr)
            return 2
    rows = [row_of(d) for d in args.runs]
    table = markdown(rows)
    sys.stdout.write(table)
    if args.markdown:
        with open(args.markdown, 'w') as f:
            f.write(table)
    if args.json:
        with open(args.json, 'w') as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == '__main__':
    sys.exit(main())

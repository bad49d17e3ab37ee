#!/usr/bin/python3
"""The gap between a dynamic run's load-sharing ratios and the quasi-static sweep's at the same
carrier angles (docs/quasistatic.md, "Against the dynamic model at low speed").

Usage: /usr/bin/python3 tools/lsr_gap.py DYN_DIR QS_DIR

DYN_DIR holds an `epicycle dynamic` run's dynamic_steps.csv and dynamic_pairs.csv, QS_DIR an
`epicycle quasistatic` sweep's quasistatic_positions.csv and quasistatic_pairs.csv whose carrier
angles include every output step's (e.g. a planet revolution at 30 rpm with --outputs-per-cycle
20 against --range planet --positions 480 --start-deg -132.92307692307692). Prints, over the
output steps, the gap |LSR_i(dynamic) - LSR_i(quasi-static)|: its largest and its median (per step
the largest over the planets), the two bands' extremes, where the largest gap is, and the gap
split by what lies in the sweep intervals on either side of the step: a friction force in a
sun-planet mesh that reverses (a loaded pair passing its pitch point), a change of a sun-planet
mesh's contact set (a tooth pair entering or leaving, a tip round taking over), or neither, with
the median there of the step's largest normal approach rate of a sun-planet pair in motion (how
hard the sun's meshes vibrate); with friction, the mean friction power of both over the angles.
"""
import csv
import sys

import numpy as np


def read(path):
    rows = [r for r in csv.reader(open(path)) if r and not r[0].startswith('#')]
    head, data = rows[0], rows[1:]
    return head, data


def columns(path):
    head, data = read(path)
    out = {}
    for i, h in enumerate(head):
        try:
            out[h] = np.array([float(r[i]) for r in data])
        except ValueError:
            pass
    return out


def sun_mesh_state(path):
    """Per carrier angle (rounded to 1e-4 deg): the sun-planet contact set and friction signs."""
    head, data = read(path)
    col = {h: i for i, h in enumerate(head)}
    state = {}
    for r in data:
        if not r[col['mesh']].startswith('sun-planet'):
            continue
        key = (r[col['mesh']], r[col['kind']], r[col['teeth']])
        contacts, signs = state.setdefault(round(float(r[col['carrier_deg']]), 4), (set(), {}))
        contacts.add(key)
        if 'friction_N' in col and r[col['friction_N']] != '':
            signs[key] = np.sign(float(r[col['friction_N']]))
    return state


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    dyn, qs = sys.argv[1], sys.argv[2]
    d = columns(dyn + '/dynamic_steps.csv')
    q = columns(qs + '/quasistatic_positions.csv')
    planets = sum(1 for k in d if k.startswith('LSR_') and not k.startswith('LSR_force'))
    order = np.argsort(q['carrier_deg'])
    qa = q['carrier_deg'][order]
    at = np.searchsorted(qa, d['carrier_deg'])
    at = np.clip(at, 0, len(qa) - 1)
    near = np.where(np.abs(qa[np.clip(at - 1, 0, None)] - d['carrier_deg']) <
                    np.abs(qa[at] - d['carrier_deg']), np.clip(at - 1, 0, None), at)
    mismatch = np.abs(qa[near] - d['carrier_deg']).max()
    if mismatch > 1e-4:
        sys.exit(f'lsr_gap: a dynamic output step is {mismatch:.3g} deg from every quasi-static '
                 'position: sweep the same carrier angles')
    j = order[near]  # the quasi-static position of each output step
    dyn_lsr = np.array([d[f'LSR_{i}'] for i in range(1, planets + 1)])
    qs_lsr = np.array([q[f'LSR_{i}'][j] for i in range(1, planets + 1)])
    gap = np.abs(dyn_lsr - qs_lsr)
    per_step = gap.max(axis=0)
    planet, step = np.unravel_index(np.argmax(gap), gap.shape)
    print(f'{len(per_step)} output steps, {planets} planets')
    print(f'gap: largest {per_step.max():.3g}, median {np.median(per_step):.2g} '
          f'(per step the largest over the planets; {np.median(gap):.2g} over every planet and step)')
    print(f'band: dynamic {dyn_lsr.min():.4f} .. {dyn_lsr.max():.4f}, quasi-static '
          f'{qs_lsr.min():.4f} .. {qs_lsr.max():.4f}: extremes apart by '
          f'{abs(dyn_lsr.min() - qs_lsr.min()):.2g} and {abs(dyn_lsr.max() - qs_lsr.max()):.2g}')
    if 'friction_power_W' in d and 'friction_power_W' in q:
        pd, pq = d['friction_power_W'].mean(), q['friction_power_W'][j].mean()
        print(f'mean friction power: dynamic {pd:.2f} W, quasi-static {pq:.2f} W '
              f'({100 * (pd / pq - 1):+.2f} %)')
    print(f'largest at step {step + 1}, t = {d["time_s"][step]:.4f} s, carrier '
          f'{d["carrier_deg"][step]:.3f} deg, planet {planet + 1}: dynamic '
          f'{dyn_lsr[planet, step]:.4f}, quasi-static {qs_lsr[planet, step]:.4f}')

    # What lies in the sweep intervals next to each step.
    state = sun_mesh_state(qs + '/quasistatic_pairs.csv')
    angles = [round(a, 4) for a in qa]

    def event(a, b):  # (contact set changes, a friction force reverses) between positions a, b
        ca, sa = state.get(angles[a], (set(), {}))
        cb, sb = state.get(angles[b], (set(), {}))
        reverses = any(k in sb and s != 0 and sb[k] == -s for k, s in sa.items())
        return ca != cb, reverses

    kinds = []
    for n in near:
        flags = [event(a, a + 1) for a in (n - 1, n) if 0 <= a and a + 1 < len(angles)]
        change = any(f[0] for f in flags)
        reverse = any(f[1] for f in flags)
        kinds.append('friction reverses' if reverse else
                     'contact set changes' if change else 'neither')
    kinds = np.array(kinds)
    # Per step the largest |normal approach rate| of the sun-planet pairs in motion: how hard the
    # sun's meshes vibrate (the quasi-static sun has none).
    head, data = read(dyn + '/dynamic_pairs.csv')
    col = {h: i for i, h in enumerate(head)}
    rate = {}
    for r in data:
        if r[col['mesh']].startswith('sun-planet'):
            t = float(r[col['time_s']])
            rate[t] = max(rate.get(t, 0.0), abs(float(r[col['overlap_rate_mm_per_s']])))
    rates = np.array([rate.get(t, 0.0) for t in d['time_s']])
    for kind in ('friction reverses', 'contact set changes', 'neither'):
        m = kinds == kind
        if m.any():
            print(f'  {kind:<20} next to {m.sum():3d} steps: gap largest {per_step[m].max():.3g}, '
                  f'median {np.median(per_step[m]):.2g}; sun-planet approach rate median '
                  f'{np.median(rates[m]):.2g} mm/s')
    top = np.argsort(-per_step)[:30]
    print('the 30 largest gaps: ' + ', '.join(f'{(kinds[top] == k).sum()} {k}'
                                             for k in ('friction reverses', 'contact set changes',
                                                       'neither')))


if __name__ == '__main__':
    main()

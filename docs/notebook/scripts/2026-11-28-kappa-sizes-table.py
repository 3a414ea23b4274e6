import json,glob,re,math,collections
rows=collections.defaultdict(list)
for f in sorted(glob.glob('/work/runs/s21/kbox/L*_s*/transport/summary.json'))+sorted(glob.glob('/work/runs/s20/seeds8/points/*/transport/summary.json')):
    j=json.load(open(f)); s=j['results']['measured']['slabs']
    L=s['box'][0]
    rows[L].append((s['conductivity'],s['conductivity_stderr'],s['particles'],s['steps'],s['J0']))
for L in sorted(rows):
    v=[r[0] for r in rows[L]]; e=[r[1] for r in rows[L]]
    m=sum(v)/len(v); sd=(sum((x-m)**2 for x in v)/(len(v)-1))**.5 if len(v)>1 else float('nan')
    rms=(sum(x*x for x in e)/len(e))**.5
    print(f"period {L:5.0f} N {rows[L][0][2]:6d} steps {rows[L][0][3]:7d} runs {len(v)}: " + ", ".join(f"{x:.2f}+-{y:.2f}" for x,y in zip(v,e)) + f" | mean {m:.3f} +- {sd/len(v)**.5 if len(v)>1 else rms:.3f} (sd {sd:.3f}, rms stated {rms:.3f})")

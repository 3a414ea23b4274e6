import csv,sys
rows=[r for r in csv.DictReader(l for l in open(sys.argv[1]+'/compare/bins.csv') if not l.startswith('#'))]
tw=sys.argv[2] if len(sys.argv)>2 else 'nominal'
q=sys.argv[3] if len(sys.argv)>3 else 'T'
xs=sorted({float(r['x']) for r in rows}); ys=sorted({float(r['y']) for r in rows},reverse=True)
d={(float(r['x']),float(r['y'])):r for r in rows}
print(f"{q} particle - {tw} (x100), rows top to bottom; last col: mean over row")
for y in ys:
    vals=[100*(float(d[(x,y)][q+'_particle'])-float(d[(x,y)][q+'_'+tw])) for x in xs]
    print(f"y={y:5.1f} "+" ".join(f"{v:+5.1f}" for v in vals)+f" | {sum(vals)/len(vals):+5.2f}")
cols=[sum(100*(float(d[(x,y)][q+'_particle'])-float(d[(x,y)][q+'_'+tw])) for y in ys)/len(ys) for x in xs]
print("colmean "+" ".join(f"{v:+5.1f}" for v in cols))

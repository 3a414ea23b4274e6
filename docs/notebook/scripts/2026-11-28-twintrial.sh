#!/bin/bash
# twintrial.sh NAME PYTHON-EDIT-OF-TRANSPORT-SUMMARY [extra run args]: the K=4 default run's twins
# rebuilt with an edited transport summary (particle and transport reused)
name=$1; edit=$2; shift 2
d=/work/runs/s21/tw/$name
rm -rf $d; mkdir -p /work/runs/s21/tw; cp -r /work/runs/s20/def4 $d
rm -rf $d/continuum $d/continuum_calibrated $d/compare $d/report
python3 - $d/transport/summary.json <<PY
import json,sys
f=sys.argv[1]; j=json.load(open(f)); m=j['results']['measured']
$edit
json.dump(j,open(f,'w'),indent=1)
PY
TWINFLOW_CACHE=off /work/main/build/app/twinflow run /work/main/cases/heated_cavity_2d.prm --ensemble 4 --out $d --threads 1 "$@" > $d.log 2>&1
python3 - $d <<'PY'
import json,sys
j=json.load(open(sys.argv[1]+'/compare/metrics.json'))
for t in j['twins']:
  x=j['twins'][t]; print(sys.argv[1].split('/')[-1], t, {k:(round(x[k]['l2'],4),round(x[k]['noise'],4)) for k in ('temperature','velocity','density') if k in x}, 'Nu', round(x.get('nusselt'),4), x.get('beyond_errors'))
PY

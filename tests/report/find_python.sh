# Sourced by the report's test scripts: sets $python to the first python3 that can import
# matplotlib and numpy (the report's only dependencies), else exits 77 (ctest: skipped).
python=""
for candidate in python3 /usr/bin/python3; do
  if command -v "$candidate" >/dev/null 2>&1 &&
     "$candidate" -c "import matplotlib, numpy" >/dev/null 2>&1; then
    python=$candidate
    break
  fi
done
if [ -z "$python" ]; then
  echo "skipped: no python3 with matplotlib and numpy (Debian: apt-get install python3-matplotlib)"
  exit 77
fi

"""The "host KEY VALUE" lines of a bench raw file (bench/host.sh) as the summary's first lines."""


def host_block(raw_path):
    rows = []
    for line in open(raw_path):
        w = line.split(None, 2)
        if len(w) == 3 and w[0] == "host":
            rows.append((w[1], w[2].strip()))
    if not rows:
        return "host: not recorded (a raw file from before bench/host.sh)\n"
    return "".join("- %s: %s\n" % row for row in rows)

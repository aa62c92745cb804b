#!/usr/bin/python3
"""Smoke test of bench/table41, bench/psnr, bench/speed and bench/decode, so that the scripts cannot rot:
table41 on 128x128 (one run, all four encoders, CSV and figure), psnr on one small synthetic image (the
edges pattern, with a PNG gAMA chunk like the Kodak photographs carry) at the three
rates of Table 4.2, speed on 128x128 (one run, all six encoders, 0.75 bpp and lossless, JSON), and
decode on 128x128 (one run, the four decoders on j2kenc's and opj_compress's streams, full resolution
and --reduce 2, JSON; then j2kdec, Grok and ojph_expand on j2kenc --ht's streams).
It checks the shape of the Markdown tables (header columns, one row per
size/encoder or image/rate/encoder, numbers that parse), not speed.

  bench_smoke_test.py --bin BUILD/bin

Exit status 0 when every check passes; otherwise the failures are listed on stderr."""

import argparse
import csv
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = os.environ.get("GPUJ2K_SOURCE_DIR") or os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)
    return condition


def run(cmd):
    proc = subprocess.run(cmd, capture_output=True, text=True)
    return proc.returncode, proc.stdout, proc.stderr


def table_after(text, heading):
    """The Markdown table that follows the line `heading`: (header cells, rows of cells)."""
    lines = text.splitlines()
    try:
        start = lines.index(heading)
    except ValueError:
        return None, []
    table = []
    for line in lines[start + 1:]:
        if line.startswith("|"):
            table.append([c.strip() for c in line.strip().strip("|").split("|")])
        elif table:
            break
    if len(table) < 2:
        return None, []
    check(all(set(c) <= set("-") for c in table[1]), f"{heading}: second line is not a separator: {table[1]}")
    return table[0], table[2:]


def number(text, what):
    try:
        v = float(text)
    except ValueError:
        check(False, f"{what}: '{text}' is not a number")
        return None
    check(math.isfinite(v) and v >= 0, f"{what}: {v} is not a finite non-negative number")
    return v


def add_gama_chunk(png):
    """Inserts gAMA 1/2.2 after IHDR, as the Kodak PNGs carry: opj_compress applies it on reading, so
    the scripts must hand every encoder a PNM copy (else opj scores ~12 dB)."""
    with open(png, "rb") as f:
        data = f.read()
    ihdr_end = 8 + 8 + 13 + 4
    body = b"gAMA" + struct.pack(">I", 45455)
    chunk = struct.pack(">I", 4) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)
    with open(png, "wb") as f:
        f.write(data[:ihdr_end] + chunk + data[ihdr_end:])


def test_table41(bin_dir, tmp):
    csv_path, plot_path = os.path.join(tmp, "t41.csv"), os.path.join(tmp, "t41.png")
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "table41"), "--sizes", "128", "--runs", "1",
                        "--bin", bin_dir, "--csv", csv_path, "--plot", plot_path, "--out", os.path.join(tmp, "t41")])
    if not check(rc == 0, f"table41 exited {rc}: {err.strip()[-2000:]}"):
        return
    check(re.search(r"^GL renderer \(GPU path\): \S", out, re.M) is not None, "table41: no GL renderer line")
    if "llvmpipe" in out:
        check("not a GPU" in out, "table41: llvmpipe named without saying it is not a GPU")
    check(re.search(r"^CPU: .+, \d+ hardware threads", out, re.M) is not None, "table41: no CPU line")

    header, rows = table_after(out, "## Per encoder (seconds)")
    check(header == ["size", "megapixels", "encoder", "total s", "GL init s", "texture s", "DWT s", "others s",
                     "process s", "bytes", "image"], f"table41 per-encoder header: {header}")
    check(len(rows) == 4, f"table41: {len(rows)} per-encoder rows, expected 4 (one per encoder)")
    prefixes = ["j2kenc --dwt cpu", "j2kenc --dwt gpu", "opj_compress", "grk_compress"]
    for row, prefix in zip(rows, prefixes):
        if not check(header and len(row) == len(header), f"table41 row has {len(row)} cells: {row}"):
            continue
        check(row[0] == "128²", f"table41 size cell: {row[0]}")
        check(abs(number(row[1], "megapixels") - 0.0164) < 1e-4, f"table41 megapixels: {row[1]}")
        check(row[2].startswith(prefix), f"table41 encoder {row[2]}, expected {prefix}")
        total = number(row[3], f"{prefix} total")
        if prefix.startswith("j2kenc"):
            parts = [number(c, f"{prefix} {h}") for c, h in zip(row[4:8], header[4:8])]
            if None not in parts and total is not None:
                # "others" is the total less the other parts, so they add up exactly before printing;
                # each of the five cells is then rounded to 3 decimals, up to 0.0005 each.
                check(abs(sum(parts) - total) <= 5 * 0.0005 + 1e-9,
                      f"{prefix}: breakdown {parts} does not add up to {total}")
            if prefix.endswith("gpu"):
                check(parts[0] is not None and parts[0] > 0, f"{prefix}: GL init {row[4]} should be positive")
            else:
                check(row[4] == "0.000" and row[5] == "0.000", f"{prefix}: GL init/texture should be 0: {row}")
        else:
            check(row[4:8] == ["n/a"] * 4, f"{prefix}: breakdown should be n/a: {row[4:8]}")
        number(row[8], f"{prefix} process")
        b = number(row[9], f"{prefix} bytes")
        target = 128 * 128 * 0.75 / 8
        check(b is not None and 0.5 * target < b <= 1.1 * target, f"{prefix}: {b} bytes for a {target:.0f}-byte target")

    header, rows = table_after(out, "## Table 4.1 layout (seconds)")
    check(header == ["image", "CPU total", "GPU total", "GL init", "texture", "DWT", "others", "cpu process",
                     "gpu process", "opj process", "grk process"], f"table41 layout header: {header}")
    check(len(rows) == 1 and rows[0][0] == "128²", f"table41 layout rows: {rows}")
    for row in rows:
        for cell, h in zip(row[1:], header[1:]):
            number(cell, f"layout {h}")

    if check(os.path.isfile(csv_path), "table41 wrote no CSV"):
        with open(csv_path, newline="", encoding="utf-8") as f:
            records = list(csv.DictReader(f))
        check([r["encoder"] for r in records] == ["cpu", "gpu", "opj", "grk"], f"table41 CSV encoders: {records}")
        for r in records:
            number(r["total_s"], "CSV total_s")
            number(r["process_s"], "CSV process_s")
        check(any(r["renderer"] for r in records if r["encoder"] == "gpu"), "table41 CSV: no renderer on the GPU row")
    if check(os.path.isfile(plot_path), "table41 wrote no figure"):
        with open(plot_path, "rb") as f:
            check(f.read(8) == b"\x89PNG\r\n\x1a\n", "table41 figure is not a PNG")


def test_psnr(bin_dir, tmp):
    image = os.path.join(tmp, "smoke.png")
    rc, _, err = run([os.path.join(bin_dir, "gentestimage"), "--pattern", "edges", "--size", "128x96", "--channels", "3",
                      "-o", image])
    if not check(rc == 0, f"gentestimage failed: {err.strip()}"):
        return
    add_gama_chunk(image)
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "psnr"), image, "--bin", bin_dir,
                        "--out", os.path.join(tmp, "psnr")])
    if not check(rc == 0, f"psnr exited {rc}: {err.strip()[-2000:]}"):
        return
    check(re.search(r"^GL renderer \(GPU path\): \S", out, re.M) is not None, "psnr: no GL renderer line")
    header, rows = table_after(out, "## Per file")
    check(header == ["image", "bpp", "encoder", "bytes", "actual bpp", "R dB", "G dB", "B dB", "all dB", "encode s",
                     "in-process s"], f"psnr per-file header: {header}")
    check(len(rows) == 12, f"psnr: {len(rows)} rows, expected 12 (3 rates x 4 encoders)")
    db = {}
    for row in rows:
        if not check(header and len(row) == len(header), f"psnr row has {len(row)} cells: {row}"):
            continue
        check(row[0] == "smoke.png", f"psnr image cell: {row[0]}")
        bpp = number(row[1], "bpp")
        check(bpp in (0.1875, 0.75, 3.0), f"psnr rate {row[1]}")
        enc = row[2].split(" v")[0]
        number(row[3], "bytes")
        actual = number(row[4], "actual bpp")
        if enc.startswith("j2kenc") and actual is not None and bpp:
            check(actual <= bpp * 1.001, f"{enc} at {bpp} bpp wrote {actual} bpp")
        values = [number(c, f"{enc} {h}") for c, h in zip(row[5:9], header[5:9])]
        number(row[9], "encode s")
        if enc.startswith("j2kenc"):
            number(row[10], "in-process s")
        else:
            check(row[10] == "n/a", f"{enc}: in-process should be n/a: {row[10]}")
        db[enc, bpp] = values[3]
    encoders = ["j2kenc --dwt cpu", "j2kenc --dwt gpu", "opj_compress", "grk_compress"]
    for enc in encoders:
        series = [db.get((enc, r)) for r in (0.1875, 0.75, 3.0)]
        if check(None not in series, f"psnr: missing rows for {enc}"):
            check(series[0] < series[1] < series[2], f"{enc}: PSNR does not rise with the rate: {series}")
    # Every encoder saw the same samples: had opj_compress applied the gAMA chunk, it would score about
    # 14 dB at 0.75 bpp and 16 dB at 3 bpp on this image, against our 19 and 32 dB.
    for r in (0.75, 3.0):
        ours, opj = db.get((encoders[0], r)), db.get(("opj_compress", r))
        if ours is not None and opj is not None:
            check(abs(ours - opj) < 3.0, f"at {r} bpp opj_compress scores {opj} dB against our {ours} dB")

    header, rows = table_after(out, "## Summary per rate and encoder (means over the images)")
    check(header is not None and len(rows) == 12, f"psnr summary: {len(rows)} rows")
    header, rows = table_after(out, "## Table 4.2 layout (PSNR in dB per channel R, G, B; mean over 1 image)")
    check(header is not None and len(header) == 5 and header[0] == "bit rate", f"psnr Table 4.2 header: {header}")
    check([r[0] for r in rows] == ["0.1875", "0.75", "3"], f"psnr Table 4.2 rows: {[r[0] for r in rows]}")
    for row in rows:
        for cell in row[1:]:
            parts = [p.strip() for p in cell.split(",")]
            check(len(parts) == 3, f"Table 4.2 cell '{cell}' should hold three channels")
            for p in parts:
                number(p, "Table 4.2 PSNR")
    check(re.search(r"^Largest \|CPU DWT - GPU DWT\| PSNR difference: \d+\.\d+ dB", out, re.M) is not None,
          "psnr: no CPU/GPU difference line")


def test_speed(bin_dir, tmp):
    json_path = os.path.join(tmp, "speed.json")
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "speed"), "--sizes", "128", "--runs", "1",
                        "--rates", "0.75,lossless", "--bin", bin_dir, "--json", json_path,
                        "--out", os.path.join(tmp, "speed")])
    if not check(rc == 0, f"speed exited {rc}: {err.strip()[-2000:]}"):
        return
    check(re.search(r"^CPU: .+, \d+ hardware threads", out, re.M) is not None, "speed: no CPU line")
    check(re.search(r"^j2kenc default DWT backend \(lossy\): \S", out, re.M) is not None,
          "speed: no line naming the default DWT backend")
    check(re.search(r"^GL renderer", out, re.M) is not None, "speed: no GL renderer line")
    check(re.search(r"^Tools: .*grk_compress", out, re.M) is not None, "speed: no tool versions line")
    heading = next((line for line in out.splitlines() if line.startswith("## 128x128: ")), None)
    if not check(heading is not None, "speed: no '## 128x128: ...' table heading"):
        return
    header, rows = table_after(out, heading)
    check(header == ["encoder", "rate", "wall s (median)", "x Grok", "CPU s (median)", "bytes", "PSNR RGB dB",
                     "peak RSS MB"], f"speed header: {header}")
    check(len(rows) == 12, f"speed: {len(rows)} rows, expected 12 (2 rates x 6 encoders)")
    prefixes = ["j2kenc (default", "j2kenc --dwt cpu", "j2kenc --ht", "opj_compress", "grk_compress", "ojph_compress"]
    for i, row in enumerate(rows):
        if not check(header and len(row) == len(header), f"speed row has {len(row)} cells: {row}"):
            continue
        rate = "0.75 bpp" if i < 6 else "lossless"
        check(row[0].startswith(prefixes[i % 6]), f"speed encoder {row[0]}, expected {prefixes[i % 6]}")
        check(row[1] == rate, f"speed rate {row[1]}, expected {rate}")
        number(row[2], f"speed {row[0]} wall s")
        x = number(row[3], f"speed {row[0]} x Grok")
        if row[0].startswith("grk_compress"):
            check(x == 1.0, f"speed: Grok's own x Grok is {row[3]}")
        cpu = number(row[4], f"speed {row[0]} CPU s")
        check(cpu is not None and cpu > 0, f"speed {row[0]}: CPU time {row[4]}")
        b = number(row[5], f"speed {row[0]} bytes")
        if rate == "lossless":
            check(row[6] == "inf (bit-exact)", f"speed {row[0]} lossless PSNR: {row[6]}")
        else:
            target = 128 * 128 * 0.75 / 8
            check(b is not None and 0.5 * target < b <= 1.1 * target, f"speed {row[0]}: {b} bytes, target {target:.0f}")
            db = number(row[6], f"speed {row[0]} PSNR")
            check(db is not None and db > 10, f"speed {row[0]}: {db} dB at 0.75 bpp")
        number(row[7].removeprefix("<= "), f"speed {row[0]} peak RSS")
    check(re.search(r"-qstep per rate .*0\.75 bpp: \d", out) is not None, "speed: no ojph_compress -qstep line")
    check("Not checked: the targets are for the 2048x2048 image" in out, "speed: no targets note")
    if check(os.path.isfile(json_path), "speed wrote no JSON"):
        with open(json_path, encoding="utf-8") as f:
            data = json.load(f)
        check([r["encoder"] for r in data["results"]] == ["j2kenc", "j2kenc-cpu", "j2kenc-ht", "opj", "grk", "ojph"] * 2,
              f"speed JSON encoders: {[r['encoder'] for r in data['results']]}")
        check(all(len(r["runs_wall_s"]) == 1 for r in data["results"]), "speed JSON: runs_wall_s should hold 1 run")
        check(all(len(r["runs_cpu_s"]) == 1 for r in data["results"]), "speed JSON: runs_cpu_s should hold 1 run")


def test_decode(bin_dir, tmp):
    json_path = os.path.join(tmp, "decode.json")
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "decode"), "--sizes", "128", "--runs", "1",
                        "--streams", "j2kenc,opj", "--bin", bin_dir, "--json", json_path,
                        "--out", os.path.join(tmp, "decode")])
    if not check(rc == 0, f"decode exited {rc}: {err.strip()[-2000:]}"):
        return
    check(re.search(r"^CPU: .+, \d+ hardware threads; every encoder and decoder runs with 2 threads", out, re.M)
          is not None, "decode: no CPU line")
    renderer = re.search(r"^GL renderer \(GPU path\): (\S+)", out, re.M)
    check(renderer is not None, "decode: no GL renderer line")
    if "llvmpipe" in out:
        check("not a GPU" in out, "decode: llvmpipe named without saying it is not a GPU")
    check(re.search(r"^Tools: j2kdec .*opj_decompress .*grk_decompress", out, re.M) is not None,
          "decode: no tool versions line")
    heading = next((line for line in out.splitlines() if line.startswith("## 128x128: ")), None)
    if not check(heading is not None, "decode: no '## 128x128: ...' table heading"):
        return
    header, rows = table_after(out, heading)
    check(header == ["stream", "rate", "resolution", "decoder", "wall s (median)", "x Grok", "peak RSS MB",
                     "vs opj_decompress"], f"decode header: {header}")
    check(len(rows) == 32, f"decode: {len(rows)} rows, expected 32 (2 rates x 2 streams x 2 resolutions x 4 decoders)")
    decoders = ["j2kdec --dwt cpu", "j2kdec --dwt gpu", "opj_decompress", "grk_decompress"]
    for i, row in enumerate(rows):
        if not check(header and len(row) == len(header), f"decode row has {len(row)} cells: {row}"):
            continue
        rate = "0.75 bpp" if i < 16 else "lossless"
        stream = ["j2kenc", "opj_compress"][i // 8 % 2]
        resolution = "full" if i % 8 < 4 else "reduce 2"
        expected = (stream, rate, resolution, decoders[i % 4])
        check(tuple(row[:3]) == expected[:3] and row[3].startswith(expected[3]), f"decode row {i}: {row[:4]}, "
              f"expected {expected}")
        if row[3].startswith("j2kdec --dwt gpu") and rate != "lossless" and renderer:
            check(renderer.group(1) in row[3], f"decode: the GPU row does not name the renderer: {row[3]}")
        number(row[4], f"decode {row[3]} wall s")
        x = number(row[5], f"decode {row[3]} x Grok")
        if row[3] == "grk_decompress":
            check(x == 1.0, f"decode: Grok's own x Grok is {row[5]}")
        number(row[6].removeprefix("<= "), f"decode {row[3]} peak RSS")
        if row[3] == "opj_decompress":
            reference = "(reference; = input)" if rate == "lossless" and resolution == "full" else "(reference)"
            check(row[7] == reference, f"decode: opj_decompress's check cell {row[7]}, expected {reference}")
        elif rate == "lossless":
            check(row[7] == "exact", f"decode: {row[3]} differs from opj_decompress on a lossless stream: {row[7]}")
        else:
            m = re.fullmatch(r"exact|max diff (\d+)", row[7])
            check(m is not None and (m.group(1) is None or int(m.group(1)) <= 2),
                  f"decode: {row[3]} at 0.75 bpp against opj_decompress: {row[7]}")
    header, rows = table_after(out, "## Summary (wall s, median; in brackets x grk_decompress)")
    check(header == ["image", "stream", "rate", "resolution"] + decoders, f"decode summary header: {header}")
    check(len(rows) == 8 and all(r[0] == "128²" for r in rows), f"decode summary rows: {rows}")
    for row in rows:
        for cell in row[4:]:
            m = re.fullmatch(r"(\d+\.\d+) \((\d+\.\d+)x\)", cell)
            check(m is not None, f"decode summary cell '{cell}' is not 'S (Xx)'")
    check("Not checked: the targets are for the 2048x2048 image" in out, "decode: no targets note")
    if check(os.path.isfile(json_path), "decode wrote no JSON"):
        with open(json_path, encoding="utf-8") as f:
            data = json.load(f)
        check([r["decoder"] for r in data["results"]] == ["j2kdec-cpu", "j2kdec-gpu", "opj", "grk"] * 8,
              f"decode JSON decoders: {[r['decoder'] for r in data['results']]}")
        check(all(len(r["runs_wall_s"]) == 1 for r in data["results"]), "decode JSON: runs_wall_s should hold 1 run")
        check(len(data["streams"]) == 4 and all(s["bytes"] > 0 for s in data["streams"]),
              f"decode JSON streams: {data['streams']}")


def test_decode_ht(bin_dir, tmp):
    """bench/decode on j2kenc --ht's streams with ojph_expand: Grok sits out the lossy stream (its refinement
    passes), ojph_expand takes part, and its column 'x ojph' appears."""
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "decode"), "--sizes", "128", "--runs", "1",
                        "--reduce", "0", "--streams", "j2kenc-ht", "--decoders", "j2kdec-cpu,grk,ojph",
                        "--bin", bin_dir, "--out", os.path.join(tmp, "decode_ht")])
    if not check(rc == 0, f"decode (HT) exited {rc}: {err.strip()[-2000:]}"):
        return
    heading = next((line for line in out.splitlines() if line.startswith("## 128x128: ")), None)
    if not check(heading is not None, "decode (HT): no '## 128x128: ...' table heading"):
        return
    header, rows = table_after(out, heading)
    check(header == ["stream", "rate", "resolution", "decoder", "wall s (median)", "x Grok", "x ojph", "peak RSS MB",
                     "vs opj_decompress"], f"decode (HT) header: {header}")
    expected = [("0.75 bpp", "j2kdec --dwt cpu"), ("0.75 bpp", "ojph_expand"), ("lossless", "j2kdec --dwt cpu"),
                ("lossless", "grk_decompress"), ("lossless", "ojph_expand")]
    check([(r[1], r[3]) for r in rows] == expected, f"decode (HT) rows: {[(r[1], r[3]) for r in rows]}")
    for row in rows:
        if not check(len(row) == len(header), f"decode (HT) row has {len(row)} cells: {row}"):
            continue
        check(row[0] == "j2kenc --ht", f"decode (HT) stream cell: {row[0]}")
        x = number(row[6], f"decode (HT) {row[3]} x ojph")
        if row[3] == "ojph_expand":
            check(x == 1.0, f"decode (HT): ojph_expand's own x ojph is {row[6]}")
        if row[1] == "lossless":
            check(row[8] == "exact", f"decode (HT): {row[3]} differs from opj_decompress on a lossless stream")


def test_errors(bin_dir):
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "psnr"), "/nonexistent/x.png", "--bin", bin_dir])
    check(rc == 1 and err.count("\n") == 1 and err.startswith("psnr: "), f"psnr on a missing file: rc {rc}, {err!r}")
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "table41"), "--sizes", "0", "--bin", bin_dir])
    check(rc == 1 and err.count("\n") == 1 and err.startswith("table41: "), f"table41 --sizes 0: rc {rc}, {err!r}")
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "speed"), "--rates", "0.75,x", "--bin", bin_dir])
    check(rc == 1 and err.count("\n") == 1 and err.startswith("speed: "), f"speed --rates 0.75,x: rc {rc}, {err!r}")
    rc, out, err = run([sys.executable, os.path.join(ROOT, "bench", "decode"), "--reduce", "0,9", "--bin", bin_dir])
    check(rc == 1 and err.count("\n") == 1 and err.startswith("decode: "), f"decode --reduce 0,9: rc {rc}, {err!r}")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"), help="folder of the built tools")
    args = p.parse_args()
    tmp = tempfile.mkdtemp(prefix="bench_smoke_")
    try:
        test_table41(args.bin, tmp)
        test_psnr(args.bin, tmp)
        test_speed(args.bin, tmp)
        test_decode(args.bin, tmp)
        test_decode_ht(args.bin, tmp)
        test_errors(args.bin)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if FAILURES:
        for f in FAILURES:
            print(f"FAIL: {f}", file=sys.stderr)
        print(f"bench_smoke_test: {len(FAILURES)} check(s) failed", file=sys.stderr)
        return 1
    print("bench_smoke_test: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Shared helpers of bench/table41, bench/psnr, bench/speed and bench/decode: finding the tools, running the
encoders, timing them, describing the machine, and printing Markdown tables.

Standard library only (matplotlib is imported by table41 for --plot, and only then)."""

import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

PROJECT_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The encoders both scripts know, in report order: key -> label.
ENCODERS = {
    "cpu": "j2kenc --dwt cpu",
    "gpu": "j2kenc --dwt gpu",
    "opj": "opj_compress",
    "grk": "grk_compress",
}

SOFTWARE_RENDERERS = ("llvmpipe", "softpipe", "swrast", "lavapipe", "swiftshader")


class BenchError(Exception):
    """A failure the scripts report as one line on stderr, exit status 1."""


def fail(program, message):
    print(f"{program}: {' '.join(str(message).split())}", file=sys.stderr)
    sys.exit(1)


# ---------------------------------------------------------------- tools

def default_bin_dir():
    return os.environ.get("GPUJ2K_BIN") or os.path.join(PROJECT_ROOT, "build", "bin")


def project_tool(bin_dir, name):
    path = os.path.join(bin_dir, name)
    if not os.access(path, os.X_OK):
        raise BenchError(f"{path} not found: build the project first (cmake --build build) or pass --bin DIR")
    return path


def system_tool(name):
    path = shutil.which(name)
    if not path:
        raise BenchError(f"{name} not found on PATH (Debian: libopenjp2-tools / grokj2k-tools)")
    return path


def tool_version(path):
    """'v2.5.0' from the 'compiled against ... library vX' line of opj_compress/grk_compress -h."""
    try:
        out = subprocess.run([path, "-h"], capture_output=True, text=True, timeout=30)
        m = re.search(r"compiled against .*?(v[0-9][0-9.]*)", out.stdout + out.stderr)
        return m.group(1).rstrip(".") if m else "version unknown"
    except (OSError, subprocess.SubprocessError):
        return "version unknown"


def parse_list(text, kind, option):
    try:
        values = [kind(x) for x in text.split(",") if x.strip() != ""]
    except ValueError:
        raise BenchError(f"{option} takes numbers separated by commas, got \"{text}\"")
    if not values or any(v <= 0 for v in values):
        raise BenchError(f"{option} takes positive numbers separated by commas, got \"{text}\"")
    return values


def parse_encoders(text):
    keys = [x.strip() for x in text.split(",") if x.strip()]
    bad = [k for k in keys if k not in ENCODERS]
    if bad or not keys:
        raise BenchError(f"--encoders takes a list of {', '.join(ENCODERS)}, got \"{text}\"")
    return [k for k in ENCODERS if k in keys]


def find_kodak_dir(given=None):
    """The Kodak photographs: --kodak DIR, else ../shared/testimages/kodak next to the project (kodimNN.png,
    or PPM conversions kodimNN.ppm where OpenImageIO is absent)."""
    candidates = [given] if given else [os.path.join(PROJECT_ROOT, "..", "shared", "testimages", "kodak")]
    for d in candidates:
        if d and any(os.path.isfile(os.path.join(d, "kodim01." + ext)) for ext in ("png", "ppm")):
            return os.path.realpath(d)
    return None


def package_version(path):
    """'0.9.0-3+b1' for a tool installed by a Debian package (dpkg -S, dpkg-query), else 'version unknown':
    for tools such as ojph_compress that print no version of their own."""
    try:
        owner = subprocess.run(["dpkg", "-S", os.path.realpath(path)], capture_output=True, text=True, timeout=30)
        if owner.returncode != 0 or ":" not in owner.stdout:
            return "version unknown"
        package = owner.stdout.split(":", 1)[0].split(",")[0].strip()
        version = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", package], capture_output=True, text=True,
                                 timeout=30)
        return version.stdout.strip() if version.returncode == 0 and version.stdout.strip() else "version unknown"
    except (OSError, subprocess.SubprocessError):
        return "version unknown"


def parse_keys(text, known, option):
    """The keys of `known` (a dict, in its order) named in the comma-separated `text`."""
    keys = [x.strip() for x in text.split(",") if x.strip()]
    bad = [k for k in keys if k not in known]
    if bad or not keys:
        raise BenchError(f"{option} takes a list of {', '.join(known)}, got \"{text}\"")
    return [k for k in known if k in keys]


def make_square_image(tools, size, kodak, folder):
    """Writes the size x size 8-bit RGB test image as PPM (every encoder reads it alike; opj_compress would
    apply a PNG's gAMA chunk): a mosaic of the Kodak photographs (tools["bench_image"]) when `kodak` is a
    folder, else a synthetic `gentestimage --pattern mix` image (tools["gentestimage"]).
    Returns (path, description)."""
    path = os.path.join(folder, f"image_{size}.ppm")
    if kodak:
        cmd = [tools["bench_image"], "mosaic", "--size", str(size), "--kodak", kodak, "-o", path]
    else:
        cmd = [tools["gentestimage"], "--pattern", "mix", "--size", f"{size}x{size}", "--channels", "3",
               "--bits", "8", "-o", path]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        raise BenchError(out.stderr.strip() or f"{os.path.basename(cmd[0])} failed")
    if kodak:
        return path, out.stdout.strip()
    return path, "SYNTHETIC gentestimage --pattern mix (RGB, 8 bits)"


# ---------------------------------------------------------------- machine

def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    import platform
    return platform.processor() or "unknown CPU"


def hardware_threads():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def renderer_of(dwt_field):
    """The GL renderer inside j2kenc's JSON 'dwt' field, e.g.
    'gpu fragment shaders (llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) Mesa 22.3.6 | egl-surfaceless)'."""
    prefix = "gpu fragment shaders ("
    if dwt_field.startswith(prefix) and dwt_field.endswith(")"):
        return dwt_field[len(prefix):-1]
    return dwt_field


def is_software_renderer(renderer):
    low = renderer.lower()
    return any(name in low for name in SOFTWARE_RENDERERS)


def renderer_lines(renderer):
    """The lines every report prints about where the 'GPU' path ran."""
    if renderer is None:
        return ["GL renderer: none (the GPU path was not run)"]
    lines = [f"GL renderer (GPU path): {renderer}"]
    if is_software_renderer(renderer):
        lines.append("NOTE: this renderer is a software rasteriser running on the CPU, not a GPU. The 'GPU' "
                     "timings measure the GPU path's overheads and correctness, not GPU speed.")
    return lines


def machine_lines(threads, who="every encoder"):
    return [f"CPU: {cpu_model()}, {hardware_threads()} hardware threads; {who} runs with {threads} threads"]


# ---------------------------------------------------------------- encoders

def _run(cmd, what):
    start = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, errors="replace")
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        text = (proc.stderr.strip() or proc.stdout.strip()).splitlines()
        tail = text[-1] if text else "(no output)"
        raise BenchError(f"{what} failed (exit {proc.returncode}): {tail}")
    return proc, wall


def run_measured(cmd, what):
    """Runs `cmd` as one child process and returns a dict: wall_s (from just before the start to the
    reaping of the process), cpu_s (the child's user plus system time over its threads, from os.wait4:
    steadier than the wall time on a shared machine), max_rss_kb (the child's peak resident set, from
    os.wait4: ru_maxrss, in KiB on Linux), rss_floor_kb, stdout and stderr (text). Output goes to
    temporary files, not pipes, so that no reading happens while the clock runs. A non-zero exit raises
    BenchError naming `what`.

    Linux keeps ru_maxrss across execve, and the child starts as a (v)fork of this Python process, so
    max_rss_kb is never below this process's own peak at the start, rss_floor_kb: a child that used less
    reads as the floor, and only a max_rss_kb above the floor is the encoder's own peak."""
    import resource
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        floor = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=out, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
        wall = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode(errors="replace")
        stderr = err.read().decode(errors="replace")
    if proc.returncode != 0:
        text = (stderr.strip() or stdout.strip()).splitlines()
        tail = text[-1] if text else "(no output)"
        raise BenchError(f"{what} failed (exit {proc.returncode}): {tail}")
    return {"wall_s": wall, "cpu_s": usage.ru_utime + usage.ru_stime, "max_rss_kb": usage.ru_maxrss,
            "rss_floor_kb": floor, "stdout": stdout, "stderr": stderr}


def encode_command(tools, encoder, image, output, bpp, threads, j2kenc_options=(), raw_bpp=24.0):
    """The command line that encodes `image` into `output` with `encoder` ("j2kenc", "opj" or "grk") at
    `bpp` bits per pixel, or losslessly when `bpp` is None: 1 tile, 1 layer, 5 decomposition levels, 9/7
    lossy (j2kenc --rate BPP; opj/grk -I -r raw_bpp/BPP, a compression ratio) or 5/3 and RCT lossless.
    `j2kenc_options` go right after j2kenc's -i and -o. Every encoder gets `threads` threads."""
    if encoder == "j2kenc":
        cmd = [tools["j2kenc"], "-i", image, "-o", output, *j2kenc_options]
        cmd += ["--lossless"] if bpp is None else ["--rate", f"{bpp:g}"]
        return cmd + ["--levels", "5", "--threads", str(threads)]
    if encoder in ("opj", "grk"):
        tool = "opj_compress" if encoder == "opj" else "grk_compress"
        cmd = [tools[tool], "-i", image, "-o", output, "-n", "6"]
        if bpp is not None:
            cmd += ["-I", "-r", f"{raw_bpp / bpp:g}"]
        return cmd + (["-threads", str(threads)] if encoder == "opj" else ["-H", str(threads)])
    raise BenchError(f"unknown encoder {encoder}")


def timing_report(stderr):
    """The last JSON line j2kenc --timing=json printed on stderr, or None."""
    report = None
    for line in stderr.splitlines():
        if line.startswith("{"):
            try:
                report = json.loads(line)
            except ValueError:
                pass
    return report


def encode(tools, key, image, output, bpp, ratio, threads):
    """Encodes `image` into `output` (.j2k) with encoder `key` at `bpp` bits per pixel (j2kenc --rate) or
    compression ratio `ratio` (opj/grk -r: raw size / coded size). 1 tile, 1 layer, 9/7, 5 levels.

    Returns a dict: wall_s (the whole process), bytes, and for j2kenc the stage times in seconds
    (total_s, gl_init_s, texture_s, dwt_s, others_s) and the 'dwt' field naming the backend."""
    if key in ("cpu", "gpu"):
        cmd = [tools["j2kenc"], "-i", image, "-o", output, "--dwt", key, "--rate", f"{bpp:g}",
               "--levels", "5", "--threads", str(threads), "--timing=json", "-q"]
    elif key == "opj":
        cmd = [tools["opj_compress"], "-i", image, "-o", output, "-I", "-n", "6", "-r", f"{ratio:g}",
               "-threads", str(threads)]
    elif key == "grk":
        cmd = [tools["grk_compress"], "-i", image, "-o", output, "-I", "-n", "6", "-r", f"{ratio:g}",
               "-H", str(threads)]
    else:
        raise BenchError(f"unknown encoder {key}")
    if os.path.exists(output):
        os.remove(output)
    proc, wall = _run(cmd, f"{ENCODERS[key]} on {os.path.basename(image)}")
    if not os.path.isfile(output):
        raise BenchError(f"{ENCODERS[key]} wrote no {output}")
    result = {"wall_s": wall, "bytes": os.path.getsize(output)}
    if key in ("cpu", "gpu"):
        report = None
        for line in proc.stderr.splitlines():
            if line.startswith("{"):
                report = json.loads(line)
        if report is None:
            raise BenchError("j2kenc printed no --timing=json line")
        st = report["stages_ms"]
        gl = (st["GL context creation"] + st["shader compilation"]) / 1000
        tex = (st["upload"] + st["download"]) / 1000
        dwt = st["DWT compute"] / 1000
        total = report["total_ms"] / 1000
        result.update(total_s=total, gl_init_s=gl, texture_s=tex, dwt_s=dwt,
                      others_s=total - gl - tex - dwt, dwt_backend=report["dwt"])
        if key == "gpu" and not report["dwt"].startswith("gpu"):
            raise BenchError(f"j2kenc --dwt gpu ran its DWT on: {report['dwt']}")
    else:
        result["total_s"] = wall
    return result


def decode(tools, codestream, output):
    if os.path.exists(output):
        os.remove(output)
    _run([tools["opj_decompress"], "-i", codestream, "-o", output], f"opj_decompress {os.path.basename(codestream)}")
    if not os.path.isfile(output):
        raise BenchError(f"opj_decompress wrote no {output}")


def psnr(tools, reference, test):
    proc, _ = _run([tools["imgpsnr"], reference, test, "--json"], f"imgpsnr {os.path.basename(test)}")
    r = json.loads(proc.stdout)
    fl = lambda v: float(v)  # "inf" -> inf
    r["channel_db"] = [fl(v) for v in r["channel_db"]]
    r["all_db"] = fl(r["all_db"])
    return r


def rss_cell(r):
    """Peak RSS in MiB of a result with max_rss_kb and rss_floor_kb (see run_measured); '<= N' where the
    reading is no more than the floor this script's own size sets."""
    mib = r["max_rss_kb"] / 1024
    return f"<= {mib:.1f}" if r["max_rss_kb"] <= r["rss_floor_kb"] else f"{mib:.1f}"


def median_run(runs, key="total_s"):
    """The run whose `key` is the median (the lower middle one for an even count), so that a row's
    stage breakdown comes from one real run and adds up to its total."""
    ordered = sorted(runs, key=lambda r: r[key])
    return ordered[(len(ordered) - 1) // 2]


def median(values):
    return statistics.median(values)


def run_order(keys, rep, case):
    """The order in which the tools run in repetition `rep` of `case` (any text naming it): a shuffle,
    the same on every machine and every run of the benchmark. The process that runs first after the
    others, or after the machine has sat idle, pays for the memory they freed: on a virtual machine
    that gives freed memory back to its host, first touches of such memory took a 2048x2048 encode
    of 0.09 s to 0.16-0.19 s. Turning a fixed order by one each repetition kept every tool behind
    the same predecessor; a shuffle gives each a different one each time."""
    import random
    order = list(keys)
    random.Random(f"{case} {rep}").shuffle(order)
    return order


# ---------------------------------------------------------------- output

def fmt(value, digits=3):
    if value is None:
        return "n/a"
    if isinstance(value, str):
        return value
    if value == float("inf"):
        return "inf"
    return f"{value:.{digits}f}"


def markdown_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    for row in rows:
        lines.append("| " + " | ".join(str(c) for c in row) + " |")
    return "\n".join(lines)


def progress(program, text):
    print(f"{program}: {text}", file=sys.stderr, flush=True)

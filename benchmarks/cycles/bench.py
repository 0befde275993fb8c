#!/usr/bin/python3
"""Exacity against Blender's Cycles on the same city (benchmarks/cycles/README.md).

    python3 benchmarks/cycles/bench.py [SKETCH] [-o WORK] [--size 320x180] [--spp 16,64]
                                       [--reference 1024] [--repeat 3] [--threads 2] [--camera SPEC]
                                       [--time-of-day HH:MM] [--landscape-trees off]

Generates SKETCH (examples/town.geojson) into WORK/city, renders its view with
`exacity render` and, from WORK/city/city.glb, with Cycles (`blender -b`), each at every
--spp with its denoiser off and on, and each against its own --reference sample render
without denoising. Prints a Markdown table: renderer, samples, CPU seconds (the median of
--repeat runs; user and system time, so that other jobs on a shared machine count less), RMSE (render/image_error.h: tone-mapped 8-bit, over 255), efficiency
1 / (seconds x RMSE^2) and its ratio to Cycles' at the same samples without denoising.
With --time-of-day (exacity render's) Cycles gets that hour's sky and, at night, the
city's street lamps (exacity_lamps); both renderers' errors are then measured with the
camera opened up as exacity render's still was (still.json's night_stops and metered_ev).
Skips (exit 0) when `blender` is absent. Uses the release build (build/release).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GRASS_ALBEDO = [0.30, 0.45, 0.20]  # kGrassAlbedo, generate/city/palette.h
MAX_BOUNCES = 8  # TraceSettings::max_depth, render/path_tracer.h


def run(args):
    done = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {done.returncode}\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return done


def cycles_has_denoiser(blender):
    probe = "import _cycles; print('OIDN', _cycles.with_openimagedenoise)"
    out = run([blender, "-b", "--factory-startup", "--python-expr", probe]).stdout
    return "OIDN True" in out


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("sketch", nargs="?", default=os.path.join(ROOT, "examples", "town.geojson"))
    p.add_argument("-o", "--work", default="/tmp/exacity-cycles")
    p.add_argument("--size", default="320x180")
    p.add_argument("--spp", default="16,64")
    p.add_argument("--reference", type=int, default=1024)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--camera", help="exacity's --camera SPEC; default: exacity render's default view")
    p.add_argument("--time-of-day", help="exacity's --time-of-day HH:MM; default: its default sun")
    p.add_argument("--landscape-trees", choices=("on", "off"), default="on",
                   help="exacity render's: off leaves out the woods' and hedgerows' trees beyond the city, which "
                        "city.glb has not, so that both renderers trace the same scene")
    p.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    p.add_argument("--reuse-cycles", action="store_true",
                   help="keep WORK/cycles from an earlier run with the same options (Cycles' images and times)")
    a = p.parse_args()

    blender = shutil.which("blender")
    if blender is None:
        print("skipped: blender is not installed (scripts/install-bench-deps.sh installs it)")
        return 0
    exacity = os.path.join(a.build, "cli", "exacity")
    sky_map = os.path.join(a.build, "benchmarks", "exacity_sky_map")
    image_error = os.path.join(a.build, "benchmarks", "exacity_image_error")
    lamps_tool = os.path.join(a.build, "benchmarks", "exacity_lamps")
    for tool in (exacity, sky_map, image_error, lamps_tool):
        if not os.access(tool, os.X_OK):
            sys.exit(f"{tool}: not built; run cmake --preset release && cmake --build --preset release")
    width, height = (int(v) for v in a.size.split("x"))
    spps = [int(v) for v in a.spp.split(",")]
    work = os.path.abspath(a.work)
    city = os.path.join(work, "city")
    reuse = a.reuse_cycles and os.path.exists(os.path.join(work, "cycles", "times.json"))
    # Only what an earlier run wrote is removed, never WORK itself.
    for folder in ("city", "exacity") if reuse else ("city", "exacity", "cycles"):
        shutil.rmtree(os.path.join(work, folder), ignore_errors=True)
    os.makedirs(os.path.join(work, "exacity"))
    os.makedirs(os.path.join(work, "cycles"), exist_ok=True)
    # Other jobs on the machine stretch every wall-clock time: the times are CPU seconds (the
    # process's user and system time over scene build, tracing and filtering), the load is
    # printed with the table.
    load_before = os.getloadavg()[0]
    run([exacity, "generate", a.sketch, "-o", city, "--quiet", "--threads", str(a.threads)])

    # The runs: (name, spp, denoise); the reference first, untimed in the table.
    # A one-sample render shows each renderer's fixed cost (scene set-up), not in the table.
    runs = [("reference", a.reference, False), ("1spp", 1, False)]
    for spp in spps:
        runs += [(f"{spp}spp", spp, False), (f"{spp}spp_denoised", spp, True)]

    # Exacity: each run --repeat times; the image is the same bytes each time (docs/design.md,
    # Determinism), the time is the median of scene build, tracing and filtering, in CPU seconds.
    exacity_times = {}
    for name, spp, denoise in runs:
        seconds = []
        for _ in range(1 if name == "reference" else a.repeat):
            png = os.path.join(work, "exacity", name + ".png")
            args = [exacity, "render", city, "--size", a.size, "--spp", str(spp), "--denoise", "on" if denoise else "off",
                    "--threads", str(a.threads), "--quiet", "-o", png]
            if a.camera:
                args += ["--camera", a.camera]
            if a.time_of_day:
                args += ["--time-of-day", a.time_of_day]
            args += ["--landscape-trees", a.landscape_trees]
            run(args)
            report = json.load(open(os.path.join(work, "exacity", name + ".json")))
            seconds.append(report["scene"]["build_cpu_s"] + report["still"]["cpu_s"] + report["still"]["denoise_cpu_s"])
        exacity_times[name] = statistics.median(seconds)
        print(f"exacity {name}: {spp} spp, {exacity_times[name]:.2f} CPU s (runs: {', '.join(f'{s:.2f}' for s in seconds)})",
              flush=True)
    camera = report["camera"]
    # The hour's sky and sun, and the camera as exacity render opened it for the reference's
    # still (the night's stops and the meter's): both renderers' errors at that exposure.
    reference = json.load(open(os.path.join(work, "exacity", "reference.json")))
    exposure = 0.25 * 2 ** (reference["night_stops"] + reference["metered_ev"])

    # Cycles: the same camera, Exacity's sky and sun, the same bounces; its denoiser only where
    # this Blender was built with OpenImageDenoise.
    denoiser = cycles_has_denoiser(blender)
    sun = json.loads(run([sky_map, os.path.join(work, "sky.exr"), "--sun-azimuth", str(reference["sun"]["azimuth"]),
                          "--sun-elevation", str(reference["sun"]["elevation"]), "--night", str(reference["night"])]).stdout)
    lamps = json.loads(run([lamps_tool, city]).stdout) if reference["lamps"] > 0 else None
    cycles_runs = [{"name": "warm_up", "spp": 1, "exr": os.path.join(work, "cycles", "warm_up.exr")}]
    for name, spp, denoise in runs:
        if denoise and not denoiser:
            continue
        for k in range(1 if name == "reference" else a.repeat):
            cycles_runs.append({"name": f"{name}#{k}", "spp": spp, "denoise": denoise,
                                "exr": os.path.join(work, "cycles", name + ".exr")})
    config = {"glb": os.path.join(city, "city.glb"), "camera": camera, "sky_map": os.path.join(work, "sky.exr"),
              "sun": sun, "lamps": lamps, "grass_albedo": GRASS_ALBEDO, "max_bounces": MAX_BOUNCES, "threads": a.threads,
              "size": [width, height], "runs": cycles_runs, "times": os.path.join(work, "cycles", "times.json")}
    if reuse:
        print("cycles: reusing the earlier run's images and times", flush=True)
    else:
        json.dump(config, open(os.path.join(work, "cycles", "config.json"), "w"), indent=1)
        run([blender, "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1", "-P",
             os.path.join(ROOT, "benchmarks", "cycles", "cycles_scene.py"),
             "--", os.path.join(work, "cycles", "config.json")])
    raw = json.load(open(config["times"]))
    cycles_times = {}
    for name, _, _ in runs:
        seconds = [s for k, s in raw.items() if k.split("#")[0] == name]
        if seconds:
            cycles_times[name] = statistics.median(seconds)
            print(f"cycles {name}: {cycles_times[name]:.2f} CPU s (runs: {', '.join(f'{s:.2f}' for s in seconds)})", flush=True)

    # Errors, each renderer against its own reference; PNGs tone-mapped alike beside the EXRs.
    def errors(folder, names):
        exrs = [os.path.join(work, folder, n + ".exr") for n in names]
        out = run([image_error, os.path.join(work, folder, "reference.exr"), *exrs, "--png",
                   "--exposure", str(exposure)]).stdout
        return {os.path.basename(line.split()[0])[:-4]: float(line.split()[1]) for line in out.splitlines()}

    exacity_errors = errors("exacity", [n for n, _, _ in runs[2:]])
    cycles_errors = errors("cycles", [n for n, _, _ in runs[2:] if n in cycles_times])

    print(f"\n{width}x{height}, {MAX_BOUNCES} bounces at most, {a.threads} threads, references {a.reference} spp; "
          f"load average {load_before:.1f} at the start, {os.getloadavg()[0]:.1f} at the end; "
          f"Cycles' denoiser {'OpenImageDenoise' if denoiser else 'absent from this Blender (built without OpenImageDenoise)'}; "
          f"sun {reference['sun']['elevation']:.1f} degrees up, {reference['lamps']} lamps, exposure {exposure:g}\n")
    print("| renderer | spp | denoiser | CPU s | RMSE | efficiency 1/(s·RMSE²) | ratio to Cycles |")
    print("|---|---|---|---|---|---|---|")
    for name, spp, denoise in runs[2:]:
        base = 1 / (cycles_times[f"{spp}spp"] * cycles_errors[f"{spp}spp"] ** 2)
        for renderer, times, errs in (("Cycles", cycles_times, cycles_errors), ("Exacity", exacity_times, exacity_errors)):
            if name not in times:
                continue
            eff = 1 / (times[name] * errs[name] ** 2)
            print(f"| {renderer} | {spp} | {'on' if denoise else 'off'} | {times[name]:.2f} | {errs[name]:.4f} | "
                  f"{eff:.0f} | {eff / base:.2f} |")
    print(f"\none sample (the fixed cost: scene set-up and one pass): Exacity {exacity_times['1spp']:.2f} CPU s, "
          f"Cycles {cycles_times['1spp']:.2f} CPU s")
    print(f"\nimages: {work}/exacity/*.png, {work}/cycles/*.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())

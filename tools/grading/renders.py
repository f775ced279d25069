"""Render checks: the stage programs run on fixed scenes, their images compared with references by
the rules of render_check.py; and the BVH speed for the leaderboard.

A check in the manifest:
  {"name", "program" (e.g. "stage5"), "scene", "args" (extra flags), "check": "pixels" or
   "statistical", "runs" (renders with seeds 1..runs), "reference" (path prefix: <prefix>-mean.pfm,
   and <prefix>-var.pfm for statistical checks), "reference_runs", "regions", "points"}
"""
import dataclasses
import pathlib
import time

import numpy as np

from . import files, images, render_check

MAX_RENDER_BYTES = 64 << 20  # a 64 x 64 check's PFM is 48 KiB


@dataclasses.dataclass
class RenderResult:
    name: str
    stage: int
    points: float
    score: float
    problems: list
    student: object = None     # mean image, or None when no image came out
    reference: object = None
    difference: object = None  # per-pixel |t| (statistical) or |student - reference| (pixels)
    failed_pixels: object = None
    rmse: float = float("nan")
    statistical: bool = False
    checked: bool = True       # False: no reference here (a student's self-grade), worth no points


def render(builder, check, seed, timeout=300):
    """Runs the check's program once in the sandbox; returns (image or None, problem or None). The
    image is read back without following links and only at the size the check expects (the
    reference's, or the args' --width and --height), and must be finite."""
    program = builder.build / "bin" / check["program"]
    if not program.is_file():
        return None, f"{check['program']} was not built"
    step = builder.deadline.timeout(timeout)
    if step <= 0:
        return None, f"not run: the time cap of {builder.deadline.cap:g} s was reached"
    slot = builder.scratch / "render"
    files.remove_tree(slot)
    slot.mkdir()
    builder.own(slot)
    scene = builder.source / check["scene"]
    log = builder.work / "render.log"
    log.write_text("")
    out = slot / "render.pfm"
    command = [str(builder.seen_path(program)), "--scene", str(builder.seen_path(scene)), "--out", str(out),
               "--seed", str(seed), *check.get("args", [])]
    result = builder.sandbox.run(command, log, step, read_only=[builder.bound(builder.source / "assets"),
                                                                 builder.bound(program)], writable=[slot], cwd=slot)
    said = files.tail_of(log, 4000).strip()
    try:
        if result.timed_out:
            return None, f"{check['program']} ran longer than {step:.0f} s"
        if result.code != 0:
            return None, f"{check['program']} exited with {result.code}: {said[-300:]}"
        try:
            image = images.decode_pfm(files.read_beneath(slot, "render.pfm", MAX_RENDER_BYTES), check["program"])
        except (OSError, ValueError, files.Refused) as error:
            return None, f"{check['program']} wrote no readable image: {error}"
        if not np.isfinite(image).all():
            return None, f"{check['program']} wrote an image with NaN or infinite values"
        return image, None
    finally:
        files.remove_tree(slot)


def render_runs(builder, check, runs):
    """`runs` renders with seeds 1..runs."""
    results = []
    for seed in range(1, runs + 1):
        image, problem = render(builder, check, seed)
        if problem:
            return None, problem
        results.append(image)
    return np.stack(results), None


def check_render(builder, instructor_root, stage, check):
    result = RenderResult(check["name"], stage, check["points"], 0.0, [], statistical=check["check"] == "statistical")
    prefix = pathlib.Path(instructor_root) / check["reference"]
    if not pathlib.Path(f"{prefix}-mean.pfm").exists():
        # A self-grade: the check is left out of the total, neither passed nor failed.
        result.points, result.checked = 0.0, False
        result.problems.append(f"not checked: the reference {check['reference']}-mean.pfm is the instructor's "
                               "(the starter tree has none)")
        return result
    stack, problem = render_runs(builder, check, check.get("runs", 1))
    if problem:
        result.problems.append(problem)
        return result
    reference = images.read_pfm(f"{prefix}-mean.pfm")
    result.student, result.reference = stack.mean(axis=0), reference
    if stack.shape[1:] != reference.shape:
        result.problems.append(f"image is {stack.shape[2]}x{stack.shape[1]}, the reference {reference.shape[1]}x{reference.shape[0]}")
        return result
    # A Monte Carlo render is noise around its mean: renders of different seeds that agree exactly
    # are not renders of those seeds (a program that ignores the seed, or writes a stored image).
    if result.statistical and stack.shape[0] > 1 and all((stack[k] == stack[0]).all() for k in range(1, stack.shape[0])):
        result.problems.append(f"the {stack.shape[0]} renders with seeds 1 to {stack.shape[0]} are identical: the "
                               "program ignores its seed")
        return result
    result.rmse = float(np.sqrt(np.mean((result.student - reference) ** 2)))
    if check["check"] == "pixels":
        result.failed_pixels, result.problems = render_check.deterministic_compare(result.student, reference)
        result.difference = np.abs(result.student - reference).max(axis=-1)
    else:
        variance = images.read_pfm(f"{prefix}-var.pfm")
        runs, reference_runs = stack.shape[0], check["reference_runs"]
        student = (result.student, stack.var(axis=0, ddof=1), runs)
        failed, t_abs, level = render_check.welch_pixel_test(student, (reference, variance, reference_runs))
        result.failed_pixels, result.difference = failed, t_abs
        if failed.any():
            result.problems.append(f"{int(failed.sum())} pixels differ from the reference beyond chance "
                                   f"(Welch's t-test, Sidak-corrected level {level:.2g} per test)")
        result.problems += render_check.region_means((stack, runs), (reference, variance, reference_runs),
                                                     check.get("regions", []))
    result.score = 0.0 if result.problems else float(check["points"])
    return result


def make_reference(builder, instructor_root, check):
    """Renders the references of one check with the instructor's own build. A pixel check's
    reference is the render with the student's seed (1); a statistical check's is the mean and
    variance of `reference_runs` renders with seeds 1001, 1002, ..., independent of the student's
    1..runs."""
    runs = check.get("reference_runs", 1)
    seeds = [1] if check["check"] == "pixels" else range(1001, 1001 + runs)
    stack = []
    for seed in seeds:
        image, problem = render(builder, check, seed)
        if problem:
            raise RuntimeError(problem)
        stack.append(image)
    stack = np.stack(stack)
    prefix = pathlib.Path(instructor_root) / check["reference"]
    prefix.parent.mkdir(parents=True, exist_ok=True)
    images.write_pfm(f"{prefix}-mean.pfm", stack.mean(axis=0))
    if check["check"] == "statistical":
        images.write_pfm(f"{prefix}-var.pfm", stack.var(axis=0, ddof=1))


def bvh_rays_per_second(builder, board):
    """Primary rays per second of the stage-3 program: two renders that differ only in samples per
    pixel, so loading the mesh and building the tree cancel out in the difference (best of
    `repeats` each)."""
    times = []
    for spp in board["spp"]:
        check = dict(board, args=[*board["args"], "--spp", str(spp)])
        best = float("inf")
        for _ in range(board.get("repeats", 3)):
            start = time.monotonic()
            _, problem = render(builder, check, 1, timeout=60)
            if problem:
                return None, problem
            best = min(best, time.monotonic() - start)
        times.append(best)
    rays = board["width"] * board["height"] * (board["spp"][1] - board["spp"][0])
    elapsed = times[1] - times[0]
    return (rays / elapsed if elapsed > 0 else None), None

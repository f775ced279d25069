"""Render checks: the stage programs run on fixed scenes, their images compared with references by
the rules of render_check.py; and the BVH speed for the leaderboard.

A check in the manifest:
  {"name", "program" (e.g. "stage5"), "scene", "args" (extra flags), "check": "pixels" or
   "statistical", "runs" (renders with seeds 1..runs), "reference" (path prefix: <prefix>-mean.pfm,
   and <prefix>-var.pfm for statistical checks), "reference_runs", "regions", "points"}
"""
import dataclasses
import pathlib
import subprocess
import tempfile
import time

import numpy as np

from . import images, render_check


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


def render(bin_dir, check, seed, out, timeout=300):
    """Runs the check's program once; returns (image or None, problem or None)."""
    program = pathlib.Path(bin_dir) / check["program"]
    command = [str(program), "--scene", check["scene"], "--out", str(out), "--seed", str(seed), *check.get("args", [])]
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except FileNotFoundError:
        return None, f"{check['program']} was not built"
    except subprocess.TimeoutExpired:
        return None, f"{check['program']} ran longer than {timeout} s"
    if done.returncode != 0:
        return None, f"{check['program']} exited with {done.returncode}: {done.stderr.strip()[-300:]}"
    try:
        return images.read_pfm(out), None
    except (OSError, ValueError) as error:
        return None, f"{check['program']} wrote no readable image: {error}"


def render_runs(bin_dir, source, check, runs):
    """`runs` renders with seeds 1..runs, from the tree's root (scene paths are relative to it)."""
    with tempfile.TemporaryDirectory() as temp:
        results = []
        for seed in range(1, runs + 1):
            out = pathlib.Path(temp) / f"run{seed}.pfm"
            check_in_tree = dict(check, scene=str(pathlib.Path(source) / check["scene"]))
            image, problem = render(bin_dir, check_in_tree, seed, out)
            if problem:
                return None, problem
            results.append(image)
        return np.stack(results), None


def check_render(bin_dir, source, instructor_root, stage, check):
    result = RenderResult(check["name"], stage, check["points"], 0.0, [], statistical=check["check"] == "statistical")
    stack, problem = render_runs(bin_dir, source, check, check.get("runs", 1))
    if problem:
        result.problems.append(problem)
        return result
    prefix = pathlib.Path(instructor_root) / check["reference"]
    reference = images.read_pfm(f"{prefix}-mean.pfm")
    result.student, result.reference = stack.mean(axis=0), reference
    if stack.shape[1:] != reference.shape:
        result.problems.append(f"image is {stack.shape[2]}x{stack.shape[1]}, the reference {reference.shape[1]}x{reference.shape[0]}")
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


def make_reference(bin_dir, instructor_root, check):
    """Renders the reference of one check with the instructor's own build. A pixel check's reference
    is the render with the student's seed (1); a statistical check's is the mean and variance of
    `reference_runs` renders with seeds 1001, 1002, ..., independent of the student's 1..runs."""
    runs = check.get("reference_runs", 1)
    seeds = [1] if check["check"] == "pixels" else range(1001, 1001 + runs)
    scene = str(pathlib.Path(instructor_root) / check["scene"])
    with tempfile.TemporaryDirectory() as temp:
        stack = []
        for seed in seeds:
            image, problem = render(bin_dir, dict(check, scene=scene), seed, pathlib.Path(temp) / "reference.pfm")
            if problem:
                raise RuntimeError(problem)
            stack.append(image)
    stack = np.stack(stack)
    prefix = pathlib.Path(instructor_root) / check["reference"]
    prefix.parent.mkdir(parents=True, exist_ok=True)
    images.write_pfm(f"{prefix}-mean.pfm", stack.mean(axis=0))
    if check["check"] == "statistical":
        images.write_pfm(f"{prefix}-var.pfm", stack.var(axis=0, ddof=1))


def bvh_rays_per_second(bin_dir, source, board):
    """Primary rays per second of the stage-3 program: two renders that differ only in samples per
    pixel, so loading the mesh and building the tree cancel out in the difference."""
    with tempfile.TemporaryDirectory() as temp:
        times = []
        for spp in board["spp"]:
            check = dict(board, args=[*board["args"], "--spp", str(spp)], scene=str(pathlib.Path(source) / board["scene"]))
            best = float("inf")
            for _ in range(board.get("repeats", 3)):
                start = time.monotonic()
                _, problem = render(bin_dir, check, 1, pathlib.Path(temp) / "speed.pfm", timeout=60)
                if problem:
                    return None, problem
                best = min(best, time.monotonic() - start)
            times.append(best)
    rays = board["width"] * board["height"] * (board["spp"][1] - board["spp"][0])
    elapsed = times[1] - times[0]
    return (rays / elapsed if elapsed > 0 else None), None

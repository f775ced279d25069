"""How the grader decides that a student's render is right, without asking for the same noise.

Deterministic stages (1-3: one ray per sample, no random choices beyond the fixed pixel pattern)
are compared pixel by pixel, forgiving silhouette edges, where a correct intersection routine may
round a grazing ray the other way. Monte Carlo stages (4, 5) are compared as statistics: K
independent renders (seeds 1..K) give a per-pixel mean and variance for the student and for the
reference, and Welch's t-test asks, pixel by pixel and channel by channel, whether the two means
can be equal. With N tests at once, one of them falls below the usual 1% by chance almost surely,
so each uses Sidak's corrected level 1 - (1 - alpha)^(1/N), which keeps the chance of any false
alarm over the whole image at alpha (as Mitsuba 3's render tests do). Region means with their
standard errors are checked as well: they catch a small bias spread over many pixels, which no
single pixel test can see.
"""
import math

import numpy as np

ALPHA = 0.01  # chance that a correct tree fails a statistical render check


def regularized_incomplete_beta(a, b, x):
    """I_x(a, b) by its continued fraction (modified Lentz), used where it converges fast."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    if x > (a + 1.0) / (a + b + 2.0):
        return 1.0 - regularized_incomplete_beta(b, a, 1.0 - x)
    log_front = math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log1p(-x)
    tiny = 1e-300
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > tiny else tiny)
    f = d
    for m in range(1, 300):
        for numerator in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                          -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + numerator * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + numerator / c
            c = c if abs(c) > tiny else tiny
            f *= c * d
        if abs(c * d - 1.0) < 1e-12:
            break
    return math.exp(log_front) * f / a


def t_test_p_value(t, dof):
    """Two-sided p-value of Student's t with `dof` degrees of freedom: I_{dof/(dof+t^2)}(dof/2, 1/2)."""
    return regularized_incomplete_beta(dof / 2.0, 0.5, dof / (dof + t * t))


def welch_pixel_test(student, reference, alpha=ALPHA):
    """Per-pixel Welch t-tests of two sets of renders, each given as (mean, variance, count).

    Returns (failed pixel mask, |t| image, the corrected level). Where both variances are zero the
    means must agree to float precision instead (a black background, the inside of an emitter)."""
    (mean_s, var_s, n_s), (mean_r, var_r, n_r) = student, reference
    se2_s, se2_r = var_s / n_s, var_r / n_r
    se2 = se2_s + se2_r
    tests = mean_s.size
    level = 1.0 - (1.0 - alpha) ** (1.0 / tests)
    failed = np.zeros(mean_s.shape, dtype=bool)
    t_abs = np.zeros(mean_s.shape)
    exact = se2 <= 0.0
    failed[exact] = np.abs(mean_s[exact] - mean_r[exact]) > 1e-5 + 1e-4 * np.abs(mean_r[exact])
    t_abs[exact] = np.where(failed[exact], np.inf, 0.0)
    for index in zip(*np.nonzero(~exact)):
        t = (mean_s[index] - mean_r[index]) / math.sqrt(se2[index])
        # Welch-Satterthwaite degrees of freedom.
        dof = se2[index] ** 2 / ((se2_s[index] ** 2 / (n_s - 1) if n_s > 1 else 0.0) +
                                 (se2_r[index] ** 2 / (n_r - 1) if n_r > 1 else 0.0) + 1e-300)
        t_abs[index] = abs(t)
        if not math.isfinite(t):
            failed[index] = True
        elif abs(t) > 3.0:  # below that no p-value comes near the corrected level
            failed[index] = t_test_p_value(t, max(dof, 1.0)) < level
    failed |= ~np.isfinite(mean_s)
    return failed.any(axis=-1), t_abs.max(axis=-1), level


def region_means(student, reference, regions, sigmas=4.0):
    """Mean radiance over each region (x0, y0, x1, y1 in pixels), student against reference,
    within `sigmas` combined standard errors (the error of a region mean from K renders)."""
    (images_s, n_s), (mean_r, var_r, n_r) = student, reference
    problems = []
    for x0, y0, x1, y1 in regions:
        per_run = images_s[:, y0:y1, x0:x1].mean(axis=(1, 2))  # K x 3
        mean_s = per_run.mean(axis=0)
        se_s = per_run.std(axis=0, ddof=1) / math.sqrt(n_s) if n_s > 1 else np.zeros(3)
        m_r = mean_r[y0:y1, x0:x1].mean(axis=(0, 1))
        # Pixels of one reference run are correlated only weakly; their variances bound the region's.
        se_r = np.sqrt(var_r[y0:y1, x0:x1].mean(axis=(0, 1)) / ((y1 - y0) * (x1 - x0)) / n_r)
        bound = sigmas * np.sqrt(se_s ** 2 + se_r ** 2) + 1e-6
        if np.any(np.abs(mean_s - m_r) > bound) or not np.all(np.isfinite(mean_s)):
            problems.append(f"region {x0}:{x1},{y0}:{y1}: mean {np.round(mean_s, 4).tolist()}, "
                            f"reference {np.round(m_r, 4).tolist()} (allowed difference {np.round(bound, 4).tolist()})")
    return problems


def edge_pixels(reference, threshold=0.05):
    """Pixels on a silhouette or shadow edge: their 3x3 neighbourhood in the reference spans more
    than `threshold` in some channel."""
    padded = np.pad(reference, ((1, 1), (1, 1), (0, 0)), mode="edge")
    h, w, _ = reference.shape
    windows = np.stack([padded[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)])
    return (windows.max(axis=0) - windows.min(axis=0)).max(axis=-1) > threshold


def deterministic_compare(student, reference, tolerance=2e-3, forgiven_fraction=0.01):
    """Pixels must match within `tolerance` (absolute plus relative); edge pixels may differ, up to
    `forgiven_fraction` of the image. Returns (failed pixel mask, problems)."""
    difference = np.abs(student - reference).max(axis=-1)
    allowed = tolerance * (1.0 + reference.max(axis=-1))
    wrong = ~(difference <= allowed)  # NaN counts as wrong
    edges = edge_pixels(reference)
    problems = []
    off_edge = wrong & ~edges
    if off_edge.any():
        problems.append(f"{int(off_edge.sum())} pixels away from edges differ by more than {tolerance} "
                        f"(largest difference {float(np.nan_to_num(difference, nan=np.inf)[off_edge].max()):.4g})")
    if (wrong & edges).sum() > forgiven_fraction * wrong.size:
        problems.append(f"{int((wrong & edges).sum())} edge pixels differ, more than {forgiven_fraction:.0%} of the image")
    return wrong, problems

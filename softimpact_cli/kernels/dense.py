"""Dense output of one step as a polynomial in the step fraction ``u`` in [0, 1].

Every method writes the monomial coefficients ``M[k]`` (k = 0..4, each of shape (dim,))
of its continuous extension, ``y(t + u h) = sum_k M[k] u**k``. Switch location, grazing
checks, penetration maxima and dense sampling all work on these coefficients, so they are
shared by every method.
"""

from numba import njit

from .layout import M0, N_SAMPLES, SAMPLE_DT, SAMPLE_T0


@njit(cache=True)
def hermite_coefficients(work, y0, y1, f0, f1, h):
    """Cubic Hermite extension from the end states and derivatives (third order)."""
    for i in range(y0.shape[0]):
        dy = y1[i] - y0[i]
        work[M0, i] = y0[i]
        work[M0 + 1, i] = h * f0[i]
        work[M0 + 2, i] = 3.0 * dy - 2.0 * h * f0[i] - h * f1[i]
        work[M0 + 3, i] = -2.0 * dy + h * f0[i] + h * f1[i]
        work[M0 + 4, i] = 0.0


@njit(cache=True)
def dense_state(work, u, out):
    """Evaluate the step's dense output at fraction ``u`` into ``out``."""
    for i in range(out.shape[0]):
        out[i] = work[M0, i] + u * (
            work[M0 + 1, i] + u * (work[M0 + 2, i] + u * (work[M0 + 3, i] + u * work[M0 + 4, i]))
        )


@njit(cache=True, inline="always")
def write_samples(work, t, h, opts, istate, sample_t, sample_y):
    """Write every sample time in (t, t + h] (and t itself for sample 0). Inlined: without
    sampling, every step pays only the test (a call passing arrays costs reference
    counting, more than the test)."""
    if opts[SAMPLE_DT] > 0.0:
        _write_samples(work, t, h, opts, istate, sample_t, sample_y)


@njit(cache=True)
def _write_samples(work, t, h, opts, istate, sample_t, sample_y):
    dt = opts[SAMPLE_DT]
    capacity = sample_t.shape[0]
    k = istate[N_SAMPLES]
    while k < capacity:
        ts = opts[SAMPLE_T0] + k * dt
        if ts > t + h * (1.0 + 1e-12):
            break
        u = (ts - t) / h if h > 0.0 else 0.0
        if u < 0.0:
            u = 0.0
        if u > 1.0:
            u = 1.0
        sample_t[k] = ts
        dense_state(work, u, sample_y[k])
        k += 1
    istate[N_SAMPLES] = k

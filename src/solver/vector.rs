//! Reductions over the dof vectors of a step: max norms (NaN-aware) and dot products. A
//! reduction over a few dozen entries, entry after entry, waits on the previous addition or
//! comparison each time (neither is reassociated by the compiler: rounding and NaNs depend on
//! the order); these keep four running partial results side by side.

const LANES: usize = 4;

/// The largest magnitude in `x`; NaN if `x` holds a NaN.
pub fn inf_norm(x: &[f64]) -> f64 {
    let mut norm = MaxMagnitude::default();
    let mut chunks = x.chunks_exact(LANES);
    for chunk in &mut chunks {
        for (lane, &v) in chunk.iter().enumerate() {
            norm.add(lane, v);
        }
    }
    for (lane, &v) in chunks.remainder().iter().enumerate() {
        norm.add(lane, v);
    }
    norm.value()
}

/// Replaces each entry `x[i]` by `update(i, x[i])` and returns the largest magnitude of the
/// new entries (NaN if one is NaN): one pass.
pub fn update_and_norm(x: &mut [f64], mut update: impl FnMut(usize, f64) -> f64) -> f64 {
    let mut norm = MaxMagnitude::default();
    let mut chunks = x.chunks_exact_mut(LANES);
    let mut start = 0;
    for chunk in &mut chunks {
        for (lane, v) in chunk.iter_mut().enumerate() {
            *v = update(start + lane, *v);
            norm.add(lane, *v);
        }
        start += LANES;
    }
    for (lane, v) in chunks.into_remainder().iter_mut().enumerate() {
        *v = update(start + lane, *v);
        norm.add(lane, *v);
    }
    norm.value()
}

/// `sum a_i b_i`.
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let b = &b[..a.len()];
    sum(a.len(), |i| a[i] * b[i])
}

/// `sum term(i)` over `i` in `0..n`.
#[inline]
pub fn sum(n: usize, term: impl Fn(usize) -> f64) -> f64 {
    let mut sums = [0.0; LANES];
    let whole = n - n % LANES;
    for start in (0..whole).step_by(LANES) {
        for (lane, s) in sums.iter_mut().enumerate() {
            *s += term(start + lane);
        }
    }
    for (lane, i) in (whole..n).enumerate() {
        sums[lane] += term(i);
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3])
}

/// The largest magnitude of the values added, NaN if one is NaN.
#[derive(Default)]
struct MaxMagnitude {
    largest: [f64; LANES],
    nan: bool,
}

impl MaxMagnitude {
    #[inline]
    fn add(&mut self, lane: usize, v: f64) {
        let a = v.abs();
        let m = &mut self.largest[lane];
        *m = if a > *m { a } else { *m };
        self.nan |= a.is_nan();
    }

    fn value(&self) -> f64 {
        if self.nan {
            f64::NAN
        } else {
            let [a, b, c, d] = self.largest;
            a.max(b).max(c.max(d))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inf_norm_is_the_largest_magnitude_and_nan_when_a_nan_is_there() {
        assert_eq!(inf_norm(&[]), 0.0);
        assert_eq!(inf_norm(&[1.0, -3.5, 2.0]), 3.5);
        assert_eq!(inf_norm(&[1.0, f64::NEG_INFINITY]), f64::INFINITY);
        assert!(inf_norm(&[1.0, f64::NAN, 5.0]).is_nan());
        assert!(inf_norm(&[f64::NAN, f64::INFINITY]).is_nan());
        assert!(inf_norm(&[2.0, -7.0, f64::NAN]).is_nan());
        // Every lane and the remainder.
        for n in 0..12 {
            for at in 0..n {
                let mut x: Vec<f64> = (0..n).map(|i| i as f64 * 0.1).collect();
                x[at] = -50.0;
                assert_eq!(inf_norm(&x), 50.0, "{n} {at}");
                let mut y = x.clone();
                assert_eq!(
                    update_and_norm(&mut y, |i, v| v + i as f64),
                    50.0 - at as f64
                );
                x[at] = f64::NAN;
                assert!(inf_norm(&x).is_nan());
            }
        }
    }

    #[test]
    fn dot_is_the_sum_of_products() {
        for n in 0..13 {
            let a: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
            let b: Vec<f64> = (0..n).map(|i| (0.5 * i as f64).cos()).collect();
            let plain: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
            assert!((dot(&a, &b) - plain).abs() < 1e-14, "{n}");
        }
    }
}

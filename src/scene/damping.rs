//! `[damping]`: Rayleigh damping `alpha M + beta K0` (added to the scene's `d`), given by its
//! coefficients or by a modal damping ratio at two frequencies.
use super::checker::Checker;
use super::file::DampingFile;
use super::SceneError;
use std::f64::consts::PI;

/// The coefficients of Rayleigh damping: `alpha` (1/s) on the mass matrix, `beta` (s) on the
/// initial tangent stiffness. A mode of circular frequency `omega` gets the damping ratio
/// `alpha / (2 omega) + beta omega / 2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rayleigh {
    pub alpha: f64,
    pub beta: f64,
}

impl Rayleigh {
    /// The coefficients that give the damping ratio `ratio` at the frequencies `f1`, `f2` (Hz):
    /// `alpha = 2 ratio w1 w2 / (w1 + w2)`, `beta = 2 ratio / (w1 + w2)`.
    pub fn from_ratio(ratio: f64, f1: f64, f2: f64) -> Rayleigh {
        let (w1, w2) = (2.0 * PI * f1, 2.0 * PI * f2);
        Rayleigh {
            alpha: 2.0 * ratio * w1 * w2 / (w1 + w2),
            beta: 2.0 * ratio / (w1 + w2),
        }
    }

    /// The damping ratio of a mode of circular frequency `omega`.
    pub fn ratio_at(&self, omega: f64) -> f64 {
        self.alpha / (2.0 * omega) + 0.5 * self.beta * omega
    }
}

pub(super) fn rayleigh(
    c: &Checker,
    raw: Option<&DampingFile>,
) -> Result<Option<Rayleigh>, SceneError> {
    let Some(d) = raw else { return Ok(None) };
    let non_negative = |x: Option<f64>, key: &str| match x {
        Some(v) if !(v.is_finite() && v >= 0.0) => {
            c.err(key, format!("{v} is out of range: must be >= 0"))
        }
        _ => Ok(x.unwrap_or(0.0)),
    };
    match (d.ratio, &d.frequencies) {
        (None, None) => {
            if d.alpha.is_none() && d.beta.is_none() {
                return c.err(
                    "[damping]",
                    "empty: give alpha and/or beta, or ratio with frequencies = [f1, f2]",
                );
            }
            Ok(Some(Rayleigh {
                alpha: non_negative(d.alpha, "damping.alpha")?,
                beta: non_negative(d.beta, "damping.beta")?,
            }))
        }
        _ if d.alpha.is_some() || d.beta.is_some() => c.err(
            "damping.ratio",
            "give alpha and beta, or ratio with frequencies, not both",
        ),
        (None, Some(_)) => c.err(
            "damping.ratio",
            "missing: the modal damping ratio at the two frequencies",
        ),
        (Some(_), None) => c.err(
            "damping.frequencies",
            "missing: the two frequencies [f1, f2] (Hz) where the ratio holds",
        ),
        (Some(ratio), Some(f)) => {
            if !(ratio.is_finite() && ratio >= 0.0) {
                return c.err(
                    "damping.ratio",
                    format!("{ratio} is out of range: must be >= 0"),
                );
            }
            let &[f1, f2] = f.as_slice() else {
                return c.err(
                    "damping.frequencies",
                    format!("{} values: give two, [f1, f2] (Hz)", f.len()),
                );
            };
            if !(f1.is_finite() && f2.is_finite() && f1 > 0.0 && f2 > 0.0) {
                return c.err(
                    "damping.frequencies",
                    format!("[{f1}, {f2}]: both must be > 0 (Hz)"),
                );
            }
            if f1 == f2 {
                return c.err(
                    "damping.frequencies",
                    format!(
                        "[{f1}, {f2}]: two different frequencies are needed to fix alpha and beta"
                    ),
                );
            }
            Ok(Some(Rayleigh::from_ratio(ratio, f1, f2)))
        }
    }
}

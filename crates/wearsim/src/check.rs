//! The rules every input obeys, one function each, shared by run files, the CLI and the Python
//! bindings so that a value is refused with the same message wherever it enters.

use crate::error::{Error, Result};

/// `value` must be finite and strictly positive.
pub fn positive(field: &str, value: f64) -> Result<()> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(Error::param(field, format!("{value} must be a finite positive number")))
    }
}

/// A grid side: an even number of pixels, at least 16 (the FFT and the periodic junction labelling
/// need at least a few pixels per side; powers of two are fastest).
pub fn grid(n: usize) -> Result<()> {
    if n < 16 || n & 1 != 0 {
        return Err(Error::param(
            "grid",
            format!("{n} must be an even number of pixels ≥ 16 (powers of two are fastest)"),
        ));
    }
    Ok(())
}

/// A junction connectivity: 4 (edge neighbours) or 8 (edge and corner neighbours).
pub fn connectivity(connectivity: u8) -> Result<()> {
    if connectivity == 4 || connectivity == 8 {
        Ok(())
    } else {
        Err(Error::param("connectivity", format!("{connectivity} must be 4 or 8")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_names_its_field() {
        assert!(positive("length", 1.0).is_ok());
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(positive("length", bad).unwrap_err().to_string().contains("`length`"));
        }
        assert!(grid(16).is_ok() && grid(14).is_err() && grid(17).is_err());
        assert!(connectivity(8).is_ok() && connectivity(6).unwrap_err().to_string().contains("`connectivity`"));
    }
}

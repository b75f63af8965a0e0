//! The periodic grid every field lives on: Nx × Ny square pixels of side Δx, so the box is
//! Lx = Nx Δx along the sliding direction x (the first array axis) and Ly = Ny Δx across it.
//! Fields are row-major, `f[i * ny + j]` with i along x.

use crate::check::{grid as check_side, positive};
use crate::error::{Error, Result};

/// A periodic grid of Nx × Ny square pixels of side Δx.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    nx: usize,
    ny: usize,
    pixel_size: f64,
}

impl Grid {
    /// A grid of `nx × ny` pixels whose side along x is `length_x` (Δx = Lx/Nx).
    pub fn new(nx: usize, ny: usize, length_x: f64) -> Result<Self> {
        check_side(nx)?;
        check_side(ny).map_err(|e| match e {
            Error::InvalidParameter { message, .. } => Error::param("grid", format!("(along y) {message}")),
            other => other,
        })?;
        if nx.saturating_mul(ny) > crate::check::MAX_GRID * crate::check::MAX_GRID {
            return Err(Error::param(
                "grid",
                format!("{nx} × {ny} pixels is more than 32-bit junction labels can index; lower `grid`"),
            ));
        }
        crate::check::scale("length", length_x)?;
        let pixel_size = length_x / nx as f64;
        positive("length", pixel_size)?;
        Ok(Self { nx, ny, pixel_size })
    }

    /// A square grid of `n × n` pixels of side `length`.
    pub fn square(n: usize, length: f64) -> Result<Self> {
        Self::new(n, n, length)
    }

    /// A grid of `nx × ny` pixels over a box `length_x × length_y`, which must have square pixels
    /// (Lx/Nx = Ly/Ny) to within round-off.
    pub fn with_lengths(nx: usize, ny: usize, length_x: f64, length_y: f64) -> Result<Self> {
        let grid = Self::new(nx, ny, length_x)?;
        crate::check::scale("length", length_y)?;
        let dy = length_y / ny as f64;
        if (dy - grid.pixel_size).abs() > 1e-9 * grid.pixel_size {
            return Err(Error::param(
                "length",
                format!(
                    "[{length_x}, {length_y}] over {nx} × {ny} pixels gives pixels of {:e} × {dy:e}; pixels must be square \
                     (Lx/Nx = Ly/Ny)",
                    grid.pixel_size
                ),
            ));
        }
        Ok(grid)
    }

    /// Pixels along x (the sliding direction; rows of a field).
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Pixels along y (the length of a row).
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Pixel side Δx.
    pub fn pixel_size(&self) -> f64 {
        self.pixel_size
    }

    /// Box side along x, Lx = Nx Δx.
    pub fn length_x(&self) -> f64 {
        self.pixel_size * self.nx as f64
    }

    /// Box side along y, Ly = Ny Δx.
    pub fn length_y(&self) -> f64 {
        self.pixel_size * self.ny as f64
    }

    /// Apparent area Lx Ly.
    pub fn area(&self) -> f64 {
        self.length_x() * self.length_y()
    }

    /// Mean (nominal) pressure p̄ = F_N/(Lx Ly) of a normal load `load` on the box: the load a
    /// contact solve is given (paper §2, where the apparent pressure sets the contact area).
    pub fn mean_pressure(&self, load: f64) -> f64 {
        load / self.area()
    }

    /// A sliding offset along x, in the length unit, as the whole pixels the top surface moves by
    /// (the composite height at an offset, paper §2): None when it is not within one period [0, Lx).
    pub fn offset_pixels(&self, offset: f64) -> Option<PixelOffset> {
        if !offset.is_finite() || offset < 0.0 || offset >= self.length_x() {
            return None;
        }
        let pixels = offset / self.pixel_size;
        Some(PixelOffset {
            pixels,
            shift: (pixels.round() as usize) % self.nx,
        })
    }

    /// Number of pixels, Nx Ny.
    pub fn pixels(&self) -> usize {
        self.nx * self.ny
    }

    /// Whether Nx = Ny.
    pub fn is_square(&self) -> bool {
        self.nx == self.ny
    }

    /// Lx/Ly, the factor that turns an integer wavenumber along y (in units of 2π/Ly) into units of
    /// 2π/Lx; exactly 1 on a square grid.
    pub fn aspect(&self) -> f64 {
        self.nx as f64 / self.ny as f64
    }
}

/// A sliding offset turned into whole pixels ([`Grid::offset_pixels`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelOffset {
    /// The offset in pixels as given, offset/Δx.
    pub pixels: f64,
    /// The whole pixels the top surface moves by, within one period [0, Nx).
    pub shift: usize,
}

impl PixelOffset {
    /// Whether the offset is a whole number of pixels (within 10⁻⁶ of one): if not, rounding
    /// moved it, which a front end says.
    pub fn is_whole(&self) -> bool {
        (self.pixels - self.pixels.round()).abs() <= 1e-6
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loads_and_offsets_in_pixels() {
        let g = Grid::new(64, 32, 2.0).unwrap();
        assert_eq!(g.mean_pressure(3.0), 3.0 / (2.0 * 1.0));
        let dx = g.pixel_size();
        let whole = g.offset_pixels(5.0 * dx).unwrap();
        assert_eq!((whole.shift, whole.is_whole()), (5, true));
        let rounded = g.offset_pixels(5.4 * dx).unwrap();
        assert_eq!(rounded.shift, 5);
        assert!(!rounded.is_whole() && (rounded.pixels - 5.4).abs() < 1e-12);
        // Just under Lx rounds to Nx pixels, which is offset 0 of the next period.
        assert_eq!(g.offset_pixels(63.9 * dx).unwrap().shift, 0);
        for outside in [-dx, 2.0, f64::NAN, f64::INFINITY] {
            assert_eq!(g.offset_pixels(outside), None, "{outside}");
        }
    }

    #[test]
    fn pixels_are_square() {
        let g = Grid::new(64, 32, 1.0).unwrap();
        assert_eq!(
            (g.nx(), g.ny(), g.pixel_size(), g.length_y(), g.aspect()),
            (64, 32, 1.0 / 64.0, 0.5, 2.0)
        );
        assert!(Grid::with_lengths(64, 32, 1.0, 0.5).is_ok());
        let e = Grid::with_lengths(64, 32, 1.0, 1.0).unwrap_err().to_string();
        assert!(e.contains("square"), "{e}");
        assert!(Grid::new(64, 15, 1.0).unwrap_err().to_string().contains("along y"));
        assert_eq!(Grid::square(16, 2.0).unwrap().aspect(), 1.0);
    }
}

//! Material parameters and the quantities derived from them (paper §2, Eq. 1).

use crate::check::positive;
use crate::error::{Error, Result};

/// How the effective modulus E* of the equivalent half-space is formed (Johnson's equivalence of two rough elastic bodies).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ModulusConvention {
    /// The half-space carries the material's E and ν: E* = E/(1−ν²), as in the paper's solver.
    #[default]
    HalfSpace,
    /// Two identical deformable bodies: E* = E/(2(1−ν²)).
    Composite,
}

impl ModulusConvention {
    /// Name as written in run files and outputs.
    pub fn name(self) -> &'static str {
        match self {
            ModulusConvention::HalfSpace => "half-space",
            ModulusConvention::Composite => "composite",
        }
    }
}

impl std::str::FromStr for ModulusConvention {
    type Err = Error;

    /// Parses the name written in run files (`modulus = "half-space"`).
    fn from_str(name: &str) -> Result<Self> {
        match name {
            "half-space" => Ok(ModulusConvention::HalfSpace),
            "composite" => Ok(ModulusConvention::Composite),
            other => Err(Error::param(
                "modulus",
                format!("\"{other}\"; use \"half-space\" (E* = E/(1−ν²)) or \"composite\" (E* = E/(2(1−ν²)))"),
            )),
        }
    }
}

/// τ̃ from a hardness H: the model's flow pressure is p_m = 3√3 τ̃ (von Mises, paper §2), the
/// hardness of the fully plastic contact, so τ̃ = H/(3√3).
pub fn shear_strength_from_hardness(hardness: f64) -> f64 {
    hardness / (3.0 * 3f64.sqrt())
}

/// τ̃ from a (tensile) yield strength σ_y: the von Mises shear yield stress τ̃ = σ_y/√3 (paper §2),
/// which makes p_m = 3 σ_y, Tabor's hardness.
pub fn shear_strength_from_yield_strength(yield_strength: f64) -> f64 {
    yield_strength / 3f64.sqrt()
}

/// 𝒢 from a mode-I fracture toughness K_Ic: Irwin's critical energy release rate in plane strain,
/// 𝒢 = K_Ic² (1 − ν²)/E (the inverse of the K_Ic = √(𝒢 E/(1 − ν²)) of the contact severity,
/// paper appendix F).
pub fn fracture_energy_from_toughness(toughness: f64, youngs_modulus: f64, poisson_ratio: f64) -> f64 {
    toughness * toughness * (1.0 - poisson_ratio * poisson_ratio) / youngs_modulus
}

/// Elastic and adhesive-wear properties of the (identical) materials of both surfaces.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Material {
    /// Young's modulus E (reduced units or Pa).
    pub youngs_modulus: f64,
    /// Poisson ratio ν, in (−1, 0.5).
    pub poisson_ratio: f64,
    /// Junction shear strength τ̃ (same unit as E).
    pub shear_strength: f64,
    /// Fracture energies 𝒢 (E·L in reduced units, J/m² in SI); one wear bookkeeping each.
    pub fracture_energies: Vec<f64>,
    /// Geometry factor f of the critical length scale (paper eq. 1), 3 by default.
    pub geometry_factor: f64,
}

/// The critical diameter d* of one fracture energy (eq. 1), also in pixels of a grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CriticalDiameter {
    /// 𝒢.
    pub fracture_energy: f64,
    /// d*, in the material's length unit.
    pub diameter: f64,
    /// d* over the pixel size.
    pub pixels: f64,
}

impl Material {
    /// Validated material; every field is checked with a message naming it.
    pub fn new(
        youngs_modulus: f64,
        poisson_ratio: f64,
        shear_strength: f64,
        fracture_energies: Vec<f64>,
        geometry_factor: f64,
    ) -> Result<Self> {
        crate::check::scale("youngs_modulus", youngs_modulus)?;
        crate::check::poisson_ratio(poisson_ratio)?;
        crate::check::scale("shear_strength", shear_strength)?;
        for &g in &fracture_energies {
            positive("fracture_energies", g)?;
        }
        positive("geometry_factor", geometry_factor)?;
        let material = Self {
            youngs_modulus,
            poisson_ratio,
            shear_strength,
            fracture_energies,
            geometry_factor,
        };
        // d* = 2 f 𝒢 μ / τ̃² must be a usable number too (p_m = 3√3 τ̃ is, with τ̃ within its range).
        for (&g, d) in material.fracture_energies.iter().zip(material.critical_diameters()) {
            if !d.is_normal() {
                return Err(Error::param(
                    "fracture_energies",
                    format!(
                        "𝒢 = {g:e} with τ̃ = {shear_strength:e} and E = {youngs_modulus:e} gives d* = {d:e}, not a usable \
                         length; check the values and their units"
                    ),
                ));
            }
        }
        Ok(material)
    }

    /// Shear modulus μ = E/(2(1+ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))
    }

    /// Flow pressure (hardness) p_m = p̃ = 3√3 τ̃ (von Mises, paper §2).
    pub fn flow_pressure(&self) -> f64 {
        3.0 * 3f64.sqrt() * self.shear_strength
    }

    /// Critical junction diameter d* = f 𝒢 / (τ̃²/(2μ)) (paper eq. 1).
    pub fn critical_diameter(&self, fracture_energy: f64) -> f64 {
        let tau = self.shear_strength;
        self.geometry_factor * fracture_energy / (tau * tau / (2.0 * self.shear_modulus()))
    }

    /// Critical diameters for every fracture energy, in the order given.
    pub fn critical_diameters(&self) -> Vec<f64> {
        self.fracture_energies
            .iter()
            .map(|&g| self.critical_diameter(g))
            .collect()
    }

    /// The critical diameter of every fracture energy, in the order given, in length units and in
    /// pixels of side `pixel_size` (what a run reports before it starts and warns about under
    /// [`crate::check::RESOLVED_PIXELS`]).
    pub fn critical_diameters_on(&self, pixel_size: f64) -> Vec<CriticalDiameter> {
        self.fracture_energies
            .iter()
            .map(|&g| {
                let diameter = self.critical_diameter(g);
                CriticalDiameter {
                    fracture_energy: g,
                    diameter,
                    pixels: diameter / pixel_size,
                }
            })
            .collect()
    }

    /// Effective modulus E* of the equivalent contact of a rigid surface on a half-space.
    pub fn effective_modulus(&self, convention: ModulusConvention) -> f64 {
        let plane_strain = self.youngs_modulus / (1.0 - self.poisson_ratio * self.poisson_ratio);
        match convention {
            ModulusConvention::HalfSpace => plane_strain,
            ModulusConvention::Composite => plane_strain / 2.0,
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn critical_diameters_in_pixels_follow_the_fracture_energies_in_order() {
        let m = super::Material::new(1.0, 0.3, 0.01, vec![0.5e-6, 1e-6], 3.0).unwrap();
        let on = m.critical_diameters_on(0.25);
        assert_eq!(on.len(), 2);
        for (c, (g, d)) in on.iter().zip(m.fracture_energies.iter().zip(m.critical_diameters())) {
            assert_eq!((c.fracture_energy, c.diameter, c.pixels), (*g, d, d / 0.25));
        }
        assert!(on[1].pixels > on[0].pixels);
    }

    use super::*;

    #[test]
    fn critical_diameter_matches_spec_check_values() {
        let m = Material::new(1.0, 0.3, 0.010, vec![0.5e-6], 3.0).unwrap();
        assert!((m.critical_diameter(0.5e-6) - 0.011_54).abs() < 1e-5);
        assert!((m.flow_pressure() - 0.051_96).abs() < 1e-5);
        // Si3N4 of Kim et al. (paper Table 1): d* = 7.65 µm.
        let si3n4 = Material::new(294e9, 0.27, 2.89e9, vec![91.97], 3.0).unwrap();
        assert!((si3n4.critical_diameter(91.97) * 1e6 - 7.65).abs() < 0.01);
    }

    #[test]
    fn hardness_yield_strength_and_toughness_convert_to_the_models_inputs() {
        // H = 3√3 τ̃ is the flow pressure; σ_y = √3 τ̃ gives p_m = 3 σ_y.
        let m = Material::new(1.0, 0.3, shear_strength_from_hardness(0.06), vec![], 3.0).unwrap();
        assert!((m.flow_pressure() - 0.06).abs() < 1e-15);
        let m = Material::new(1.0, 0.3, shear_strength_from_yield_strength(0.02), vec![], 3.0).unwrap();
        assert!((m.flow_pressure() - 0.06).abs() < 1e-15);
        // Si3N4 of Kim et al. (paper Table 1): 𝒢 = 91.97 J/m² with E = 294 GPa, ν = 0.27 is
        // K_Ic = √(𝒢 E/(1 − ν²)) = 5.40 MPa√m, and back.
        let k = (91.97f64 * 294e9 / (1.0 - 0.27 * 0.27)).sqrt();
        assert!((k / 1e6 - 5.40).abs() < 0.01, "{k}");
        assert!((fracture_energy_from_toughness(k, 294e9, 0.27) - 91.97).abs() < 1e-9);
    }

    #[test]
    fn modulus_conventions() {
        let m = Material::new(2.0, 0.5f64.next_down(), 0.01, vec![], 3.0).unwrap();
        let hs = m.effective_modulus(ModulusConvention::HalfSpace);
        assert!((m.effective_modulus(ModulusConvention::Composite) - hs / 2.0).abs() < 1e-12);
    }

    #[test]
    fn bad_values_name_their_field() {
        let e = Material::new(-1.0, 0.3, 0.01, vec![], 3.0).unwrap_err().to_string();
        assert!(e.contains("youngs_modulus"), "{e}");
        let e = Material::new(1.0, 0.5, 0.01, vec![], 3.0).unwrap_err().to_string();
        assert!(e.contains("poisson_ratio"), "{e}");
        let e = Material::new(1.0, 0.3, f64::NAN, vec![], 3.0).unwrap_err().to_string();
        assert!(e.contains("shear_strength"), "{e}");
        // Moduli and strengths outside the range in which results are representable.
        let e = Material::new(1.0, 0.3, 1e308, vec![], 3.0).unwrap_err().to_string();
        assert!(e.contains("shear_strength") && e.contains("1e-90 … 1e90"), "{e}");
        let e = Material::new(5e-324, 0.3, 0.01, vec![0.5e-6], 3.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("youngs_modulus") && e.contains("1e-90 … 1e90"), "{e}");
        // A derived d* that underflows.
        let e = Material::new(1.0, 0.3, 0.01, vec![1e-320], 3.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("fracture_energies") && e.contains("d*"), "{e}");
    }
}

//! Text in raster figures (PNG, GIF) drawn with each glyph where the font puts it.
//!
//! plotters 0.3.7 rasterises a string glyph by glyph but places each outline at the pen position
//! without its left side bearing, so a narrow glyph ("1", ".") sits at the left of its advance and
//! leaves a gap after it: "job 19" printed as "job 1 9", "0.012 E" as "0.01 2 E". [`Raster`] wraps a
//! bitmap backend and draws text itself with the bundled font, each glyph's outline at its own pixel
//! bounds; everything else goes to the wrapped backend. SVG output is text and never had the gap.
//!
//! DejaVu Sans has no script capitals, so the paper's 𝒢 comes from STIX General (shipped beside it
//! in `assets/`, under its licence), the font of any glyph DejaVu Sans lacks.

use ab_glyph::{point, Font, FontRef, ScaleFont};
use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontTransform};

/// The bundled DejaVu Sans, the font every figure's text is drawn in.
pub const FONT_BYTES: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// STIX General, for the glyphs DejaVu Sans lacks (the script 𝒢 of the fracture energy).
pub const FALLBACK_BYTES: &[u8] = include_bytes!("../assets/STIXGeneral.ttf");

/// The fonts text is drawn in: DejaVu Sans, then STIX General for what it lacks.
pub fn fonts() -> [FontRef<'static>; 2] {
    [
        FontRef::try_from_slice(FONT_BYTES).expect("the bundled font is valid"),
        FontRef::try_from_slice(FALLBACK_BYTES).expect("the bundled font is valid"),
    ]
}

/// A raster backend whose text keeps the font's glyph placement (see the module doc).
pub struct Raster<B> {
    inner: B,
    fonts: [FontRef<'static>; 2],
}

impl<B> Raster<B> {
    pub fn new(inner: B) -> Self {
        Self { inner, fonts: fonts() }
    }
}

/// The pixels of `text` at `size` (in plotters' font size, pixels per em × 1.24 as its layout
/// assumes), relative to the text's pen origin with the baseline at `size / 2` below it, as plotters
/// places it: (x, y, coverage in 0 … 1). Each character comes from the first of `fonts` that has it.
pub fn glyph_pixels(fonts: &[FontRef<'_>], size: f64, text: &str) -> Vec<(i32, i32, f32)> {
    let mut pixels = Vec::new();
    let mut pen = 0f32;
    let mut prev = None;
    for c in text.chars() {
        let (f, font) = fonts
            .iter()
            .enumerate()
            .find(|(_, f)| f.glyph_id(c).0 != 0)
            .unwrap_or((0, &fonts[0]));
        // ab_glyph scales a font to its ascent-to-descent height; the fallback is scaled to the
        // same em as the first font, so its glyphs come out the same size.
        let em = |f: &FontRef<'_>| f.height_unscaled() / f.units_per_em().unwrap_or(1000.0);
        let scaled = font.as_scaled(size as f32 * em(font) / em(&fonts[0]));
        let id = scaled.glyph_id(c);
        if let Some((pf, p)) = prev {
            if pf == f {
                pen += scaled.kern(p, id);
            }
        }
        prev = Some((f, id));
        let glyph = id.with_scale_and_position(scaled.scale(), point(pen, 0.0));
        if let Some(outline) = scaled.outline_glyph(glyph) {
            let bounds = outline.px_bounds();
            let (x0, y0) = (bounds.min.x as i32, (size as f32 / 2.0 + bounds.min.y) as i32);
            outline.draw(|x, y, c| pixels.push((x0 + x as i32, y0 + y as i32, c)));
        }
        pen += scaled.h_advance(id);
    }
    pixels
}

impl<B: DrawingBackend> DrawingBackend for Raster<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.inner.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.present()
    }
    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_pixel(point, color)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.fill_polygon(vert, style)
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        (iw, ih): (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.inner.blit_bitmap(pos, (iw, ih), src)
    }

    /// plotters' own text placement (anchor from the layout box, rotation), with the glyphs of
    /// [`glyph_pixels`].
    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let ((min_x, min_y), (max_x, max_y)) = style
            .layout_box(text)
            .map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        let (width, height) = (max_x - min_x, max_y - min_y);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let transform: FontTransform = style.transform();
        let (w, h) = self.inner.get_size();
        for (x, y, coverage) in glyph_pixels(&self.fonts, style.size(), text) {
            let (x, y) = transform.transform(x + dx - min_x, y + dy - min_y);
            let (x, y) = (pos.0 + x, pos.1 + y);
            if x >= 0 && x < w as i32 && y >= 0 && y < h as i32 {
                let pixel = BackendColor {
                    alpha: color.alpha * coverage.clamp(0.0, 1.0) as f64,
                    rgb: color.rgb,
                };
                self.inner.draw_pixel((x, y), pixel)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The columns of `text` that hold ink.
    fn inked_columns(fonts: &[FontRef<'_>], text: &str) -> Vec<i32> {
        let mut columns: Vec<i32> = glyph_pixels(fonts, 48.0, text)
            .into_iter()
            .filter(|p| p.2 > 0.3)
            .map(|p| p.0)
            .collect();
        columns.sort_unstable();
        columns.dedup();
        columns
    }

    /// The widest run of empty columns between the first and the last inked one.
    fn widest_gap(columns: &[i32]) -> i32 {
        columns.windows(2).map(|w| w[1] - w[0] - 1).max().unwrap_or(0)
    }

    #[test]
    fn digits_after_a_one_keep_their_spacing() {
        let font = fonts();
        // "1" is narrow with a wide left bearing: drawn at the pen position (as plotters 0.3.7
        // does) its ink starts at column 0 and "19" shows a gap of 12 px, against 8 px in "91".
        let one = inked_columns(&font, "1");
        assert!(
            one[0] >= 4,
            "the 1's left bearing (5 px at 48 px) is kept: ink from column {}",
            one[0]
        );
        let gap_19 = widest_gap(&inked_columns(&font, "19"));
        let gap_91 = widest_gap(&inked_columns(&font, "91"));
        assert!(
            gap_19 <= gap_91 + 1,
            "gap after the 1 ({gap_19} px) as between 9 and 1 ({gap_91} px)"
        );
    }

    #[test]
    fn the_papers_symbols_have_glyphs() {
        let fonts = fonts();
        for c in ['τ', '\u{303}', '𝒢', 'ₘ', '₊', '*', '²', '⁻'] {
            assert!(fonts.iter().any(|f| f.glyph_id(c).0 != 0), "no glyph for {c:?}");
        }
        // The combining tilde of τ̃ sits over the τ, not after it.
        let tau = inked_columns(&fonts, "τ");
        let tilde = inked_columns(&fonts, "τ\u{303}");
        assert!(tilde.last() <= Some(&(tau.last().unwrap() + 2)), "{tau:?} {tilde:?}");
    }
}

//! SVG to PNG and to PDF. The SVG a chart is drawn as is read by usvg with the
//! embedded font as the only one (no system fonts); resvg renders it anti-aliased at
//! [`RASTER_SCALE`] times its size, svg2pdf writes it as vector PDF with the font
//! embedded (subset) and the page as wide as the picture prints.

use std::sync::{Arc, OnceLock};

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{fontdb, Options, Tree};

use super::style::{FAMILY, UNITS_PER_MM};
use super::{PlotError, FONT};

/// Pixels of the PNG per unit of the SVG.
pub const RASTER_SCALE: f32 = 2.0;

/// The font database: only the embedded DejaVu Sans, serving every generic family.
fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut database = fontdb::Database::new();
            database.load_font_data(FONT.to_vec());
            database.set_sans_serif_family(FAMILY);
            database.set_serif_family(FAMILY);
            database.set_monospace_family(FAMILY);
            Arc::new(database)
        })
        .clone()
}

/// The SVG read, its text laid out in the embedded font.
fn tree(svg: &str) -> Result<Tree, PlotError> {
    let options = Options {
        font_family: FAMILY.to_string(),
        fontdb: fonts(),
        ..Options::default()
    };
    Tree::from_str(svg, &options).map_err(|e| PlotError::Draw(format!("the SVG cannot be read: {e}")))
}

/// The PNG of `svg` at [`RASTER_SCALE`].
pub fn png(svg: &str) -> Result<Vec<u8>, PlotError> {
    let tree = tree(svg)?;
    let size = tree.size().to_int_size().scale_by(RASTER_SCALE).ok_or_else(too_large)?;
    let mut pixmap = Pixmap::new(size.width(), size.height()).ok_or_else(too_large)?;
    resvg::render(
        &tree,
        Transform::from_scale(RASTER_SCALE, RASTER_SCALE),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .map_err(|e| PlotError::Draw(format!("encoding the PNG: {e}")))
}

/// The PDF of `svg`: vector paths, text as text in the embedded font, the page
/// [`UNITS_PER_MM`] units of the SVG per millimetre (a figure panel 85 mm wide).
pub fn pdf(svg: &str) -> Result<Vec<u8>, PlotError> {
    let tree = tree(svg)?;
    let page = svg2pdf::PageOptions {
        dpi: (UNITS_PER_MM * 25.4) as f32,
    };
    svg2pdf::to_pdf(&tree, svg2pdf::ConversionOptions::default(), page)
        .map_err(|e| PlotError::Draw(format!("writing the PDF: {e}")))
}

fn too_large() -> PlotError {
    PlotError::Draw("the picture is too large to rasterise".to_string())
}

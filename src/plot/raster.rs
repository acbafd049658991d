//! SVG to PNG: the SVG a chart is drawn as, rendered anti-aliased by resvg at
//! [`RASTER_SCALE`] times its size, with the embedded font (no system fonts).

use std::sync::{Arc, OnceLock};

use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{fontdb, Options, Tree};

use super::{PlotError, FONT};

/// Pixels of the PNG per pixel of the SVG.
pub const RASTER_SCALE: f32 = 2.0;

/// The font database: only the embedded DejaVu Sans, serving every generic family.
fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut database = fontdb::Database::new();
            database.load_font_data(FONT.to_vec());
            database.set_sans_serif_family("DejaVu Sans");
            database.set_serif_family("DejaVu Sans");
            database.set_monospace_family("DejaVu Sans");
            Arc::new(database)
        })
        .clone()
}

/// The PNG of `svg` at [`RASTER_SCALE`].
pub fn png(svg: &str) -> Result<Vec<u8>, PlotError> {
    let options = Options {
        font_family: "DejaVu Sans".to_string(),
        fontdb: fonts(),
        ..Options::default()
    };
    let tree = Tree::from_str(svg, &options).map_err(|e| PlotError::Draw(format!("the SVG cannot be read: {e}")))?;
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

fn too_large() -> PlotError {
    PlotError::Draw("the picture is too large to rasterise".to_string())
}

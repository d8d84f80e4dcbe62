//! Writes a picture of one tile type built to the thesis design: the README's picture.
//!
//! `cargo run --release -p foldchain-print --example tile_picture -- SL docs/print-tile-SL.png`
//! (a PNG drawn with a depth buffer; an `.svg` name gives the vector picture)

use foldchain::{Design, Tile};
use foldchain_print::{mesh_png, mesh_svg, PartOptions, TilePart, View};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let tile: Tile = args.get(1).map_or("SL", String::as_str).parse()?;
    let out = args
        .get(2)
        .cloned()
        .unwrap_or_else(|| format!("tile-{tile}.svg"));
    let part = TilePart::new(tile, &Design::thesis(), &PartOptions::default())?;
    let title = format!(
        "{tile} (turned: {}), thesis design, FDM clearance {} mm: {} triangles",
        tile.turned(),
        part.options.clearance,
        part.mesh.triangles.len()
    );
    if out.ends_with(".png") {
        let png = mesh_png(&part.mesh, &View::default()).ok_or("PNG encoding failed")?;
        std::fs::write(&out, png)?;
    } else {
        std::fs::write(&out, mesh_svg(&part.mesh, &title, &View::default()))?;
    }
    Ok(())
}

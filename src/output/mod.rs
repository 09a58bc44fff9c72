//! The output stage: shells made of the stitched patches, the STEP written with each face's thickness, the
//! report assembled with its topology summary, every file written atomically. Also `midsurf inspect`'s and
//! `midsurf pairs`'s text.

pub mod assemble;
pub mod coverage;
pub mod files;
pub mod inspect;
pub mod pairs_table;
pub mod pending;
pub mod report;
pub mod shells;
pub mod topology;

/// Rounded to `digits` decimals; -0 becomes 0 so the text does not flicker.
pub fn round(x: f64, digits: i32) -> f64 {
    let scale = 10f64.powi(digits);
    let r = (x * scale).round() / scale;
    if r == 0.0 {
        0.0
    } else {
        r
    }
}

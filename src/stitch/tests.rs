use super::*;

#[test]
fn open_edges_are_said_once_with_their_patches() {
    let free = FreeEdges { rim_edges: 4, rim_length: 40.0, open_edges: 3, open_length: 2.5 };
    let w = open_edges_warning(&free, &BTreeSet::from([6, 0])).unwrap();
    assert_eq!(w.code, "open_edges");
    assert!(w.message.starts_with("3 free edge(s), 2.500 mm") && w.message.contains("(patches 1, 7)"), "{}", w.message);
    assert!(open_edges_warning(&FreeEdges { open_edges: 0, ..free }, &BTreeSet::new()).is_none());
}

"""free: handles are dropped, counted, and never reused."""

from shapes import box


def test_free_drops_handles_and_counts_only_known_ones(client, tmp_path):
    handle = client.load(box(), tmp_path)
    assert client.ok("free", handles=[handle, handle + 100]) == {"freed": 1}
    err = client.err("describe", handle=handle)
    assert err["code"] == "bad_args"
    assert str(handle) in err["message"]
    assert client.ok("free", handles=[handle]) == {"freed": 0}


def test_handles_are_never_reused(client, tmp_path):
    first = client.load(box(), tmp_path, "a.step")
    client.ok("free", handles=[first])
    second = client.load(box(), tmp_path, "b.step")
    assert second > first > 0


def test_free_rejects_non_handles(client):
    for bad in ([0], [-3], ["1"], [True], 5):
        assert client.err("free", handles=bad)["code"] == "bad_args"

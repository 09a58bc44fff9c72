"""ping."""


def test_ping(client):
    assert client.ok("ping") == {"pong": True}


def test_ping_ignores_args(client):
    assert client.ok("ping", anything=1) == {"pong": True}

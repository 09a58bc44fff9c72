"""shutdown: answers, then the loop stops (the process exit is covered in test_protocol)."""

import io

from midsurf_sidecar.server import serve


def test_shutdown_stops_the_loop_before_later_requests():
    requests = io.BytesIO(
        b'{"id":0,"op":"hello","args":{"protocol":1}}\n'
        b'{"id":1,"op":"shutdown","args":{}}\n'
        b'{"id":2,"op":"ping","args":{}}\n'
    )
    replies = io.StringIO()
    serve(requests, replies)
    lines = replies.getvalue().splitlines()
    assert len(lines) == 2
    assert lines[1] == '{"id":1,"ok":{"bye":true}}'


def test_shutdown_is_honoured_before_hello(fresh_client):
    assert fresh_client.ok("shutdown") == {"bye": True}
    assert fresh_client.session.finished

"""hello: the handshake, and what the session answers before and around it."""

import json
import os
import subprocess
import sys
from pathlib import Path

from midsurf_sidecar.server import PROTOCOL_VERSION

SIDECAR_DIR = Path(__file__).resolve().parents[1]


def test_hello_reports_versions(fresh_client):
    ok = fresh_client.ok("hello", protocol=PROTOCOL_VERSION)
    assert ok["protocol"] == PROTOCOL_VERSION
    assert ok["python"] == ".".join(map(str, sys.version_info[:3]))
    assert ok["occt"].startswith("8.")
    assert list(ok) == ["protocol", "python", "occt"]


def test_protocol_mismatch_names_both_versions(fresh_client):
    err = fresh_client.err("hello", protocol=PROTOCOL_VERSION + 1)
    assert err["code"] == "protocol_mismatch"
    assert str(PROTOCOL_VERSION + 1) in err["message"] and str(PROTOCOL_VERSION) in err["message"]
    assert "scripts/setup" in err["message"]
    # A failed handshake is no handshake.
    assert fresh_client.err("ping")["code"] == "no_handshake"


def test_hello_without_protocol_is_bad_args(fresh_client):
    assert fresh_client.err("hello")["code"] == "bad_args"


def test_requests_before_hello_get_no_handshake(fresh_client):
    assert fresh_client.err("ping")["code"] == "no_handshake"
    assert fresh_client.err("load_step", path="/nonexistent.step")["code"] == "no_handshake"
    fresh_client.ok("hello", protocol=PROTOCOL_VERSION)
    assert fresh_client.ok("ping") == {"pong": True}


def test_unknown_op(client):
    err = client.err("frobnicate")
    assert err["code"] == "unknown_op"
    assert "frobnicate" in err["message"]


def test_malformed_lines_get_an_error_with_null_id(client):
    for line in (b"not json", b"[1, 2]", b'{"op": "ping"}', b'{"id": -1, "op": "ping"}', b"\xff\xfe", b'{"id": true}'):
        reply = client.session.respond(line)
        assert reply["id"] is None
        assert reply["err"]["code"] == "bad_args"


def test_args_must_be_an_object(client):
    reply = client.session.respond(b'{"id": 7, "op": "ping", "args": [1]}')
    assert reply == {"id": 7, "err": {"code": "bad_args", "message": reply["err"]["message"]}}


def test_python_without_ocp_answers_ocp_missing():
    # -S leaves site-packages (where OCP lives) off sys.path.
    process = subprocess.run(
        [sys.executable, "-S", "-m", "midsurf_sidecar"],
        input=json.dumps({"id": 0, "op": "hello", "args": {"protocol": PROTOCOL_VERSION}}) + "\n",
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(SIDECAR_DIR)},
        timeout=60,
    )
    assert process.returncode == 0
    reply = json.loads(process.stdout)
    assert reply["id"] == 0
    assert reply["err"]["code"] == "ocp_missing"
    assert "OCP" in reply["err"]["message"] and "scripts/setup" in reply["err"]["message"]


def test_op_must_be_a_string(client):
    reply = client.session.respond(b'{"id": 3, "op": ["ping"]}')
    assert reply["id"] == 3 and reply["err"]["code"] == "bad_args"

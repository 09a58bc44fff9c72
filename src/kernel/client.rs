//! Request/reply over a transport, the handshake, per-op timeouts, and restarting a dead sidecar.

use std::time::Duration;

use serde::de::DeserializeOwned;
use serde_json::Value;

use super::process::ProcessTransport;
use super::protocol::{self, Hello, Request, PROTOCOL_VERSION};
use super::python::{self, Launch};
use super::{SidecarError, Transport, TransportError};

/// How long each op may take before the sidecar is considered stuck. Importing OCP takes ~1 s warm and much
/// longer on a cold disk; kernel ops on the largest real parts take seconds, so minutes mean a hang.
/// `MIDSURF_TIMEOUT_SECS` replaces every figure (tests use it to provoke timeouts quickly).
pub fn timeout_for(op: &str) -> Duration {
    if let Some(after) = super::timeout::timeout_override() {
        return after;
    }
    let secs = match op {
        "hello" => 120,
        "ping" | "free" | "shutdown" => 10,
        _ => 600,
    };
    Duration::from_secs(secs)
}

/// A handshaken connection to one sidecar.
pub struct Client<T: Transport> {
    transport: T,
    next_id: u64,
    pub hello: Hello,
}

impl<T: Transport> Client<T> {
    /// Sends `hello` (always request id 0) and checks the protocol version.
    pub fn connect(transport: T) -> Result<Client<T>, SidecarError> {
        let mut client =
            Client { transport, next_id: 0, hello: Hello { protocol: 0, python: String::new(), occt: String::new() } };
        let hello: Hello = client.call(&Request::Hello { protocol: PROTOCOL_VERSION })?;
        if hello.protocol != PROTOCOL_VERSION {
            return Err(SidecarError::Op {
                op: "hello".into(),
                code: "protocol_mismatch".into(),
                message: format!(
                    "the sidecar speaks protocol {} but midsurf expects {PROTOCOL_VERSION}; run scripts/setup",
                    hello.protocol
                ),
            });
        }
        client.hello = hello;
        Ok(client)
    }

    /// Sends one request and decodes its `ok` payload into `R`.
    pub fn call<R: DeserializeOwned>(&mut self, request: &Request) -> Result<R, SidecarError> {
        let op = request.op();
        let value = self.call_value(request)?;
        serde_json::from_value(value).map_err(|e| SidecarError::BadReply {
            op: op.to_string(),
            why: format!("unexpected reply shape ({e})"),
            line: String::new(),
        })
    }

    pub fn call_value(&mut self, request: &Request) -> Result<Value, SidecarError> {
        let op = request.op();
        let id = self.next_id;
        self.next_id += 1;
        let died = |t: &T| SidecarError::Died { op: op.to_string(), stderr: t.diagnostics() };
        self.transport.send(&protocol::encode(id, request)).map_err(|_| died(&self.transport))?;
        let after = timeout_for(op);
        match self.transport.recv(after) {
            Ok(line) => protocol::decode(id, op, &line),
            Err(TransportError::Closed) => Err(died(&self.transport)),
            Err(TransportError::Timeout) => {
                Err(SidecarError::Timeout { op: op.to_string(), after, stderr: self.transport.diagnostics() })
            }
        }
    }
}

/// Whether the sidecar's diagnostics end with its death by a signal sent from outside (not a crash).
pub(crate) fn killed_from_outside(stderr: &str) -> bool {
    let last = stderr.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("");
    last.strip_prefix(super::process::KILLED_BY)
        .and_then(|rest| rest.split_whitespace().next())
        .is_some_and(|sig| ["9", "15", "1", "2"].contains(&sig))
}

/// The real sidecar process. A sidecar that died or hung is dropped (killed and reaped) and the next call
/// starts a new one; handles of the old process are gone, so the caller must reload what it needs.
pub struct Sidecar {
    launch: Launch,
    client: Option<Client<ProcessTransport>>,
}

impl Sidecar {
    /// A sidecar, its booleans on one thread when `serial_booleans` (see `Launch`).
    pub fn start(serial_booleans: bool) -> Result<Sidecar, SidecarError> {
        let launch = python::Launch { serial_booleans, ..python::locate()? };
        let mut sidecar = Sidecar { launch, client: None };
        sidecar.connected()?;
        Ok(sidecar)
    }

    fn connected(&mut self) -> Result<&mut Client<ProcessTransport>, SidecarError> {
        if self.client.is_none() {
            let transport = ProcessTransport::spawn(&self.launch)?;
            self.client = Some(Client::connect(transport).map_err(|e| self.explain_start_failure(e))?);
        }
        Ok(self.client.as_mut().expect("client was just connected"))
    }

    /// A sidecar that dies before the handshake is almost always a broken install: say which command fixes it.
    fn explain_start_failure(&self, error: SidecarError) -> SidecarError {
        let python = self.launch.python.display();
        match error {
            // Killed from outside (SIGKILL, SIGTERM: the OOM killer, a user): the install is not at fault.
            SidecarError::Died { ref stderr, .. } if killed_from_outside(stderr) => error,
            SidecarError::Died { stderr, .. } => SidecarError::Spawn {
                why: format!(
                    "{python} exited before the handshake{}; run scripts/setup or set MIDSURF_PYTHON",
                    super::last_words(&stderr)
                ),
            },
            SidecarError::Op { code, message, .. } if code == "ocp_missing" || code == "protocol_mismatch" => {
                SidecarError::Spawn { why: format!("{python}: {message}") }
            }
            other => other,
        }
    }

    /// The versions the sidecar reported (not used by the commands yet; kept for diagnostics).
    #[allow(dead_code)]
    pub fn hello(&mut self) -> Result<Hello, SidecarError> {
        Ok(self.connected()?.hello.clone())
    }

    pub fn call<R: DeserializeOwned>(&mut self, request: &Request) -> Result<R, SidecarError> {
        let result = self.connected()?.call(request);
        if matches!(
            result,
            Err(SidecarError::Died { .. } | SidecarError::Timeout { .. } | SidecarError::BadReply { .. })
        ) {
            self.client = None;
        }
        result
    }

    /// Asks the sidecar to exit and waits for it; dropping does the same more bluntly.
    pub fn shutdown(mut self) {
        if let Some(mut client) = self.client.take() {
            let _ = client.call_value(&Request::Shutdown {});
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::VecDeque;

    /// Replays scripted reply lines and records what was sent.
    struct Fake {
        sent: Vec<String>,
        replies: VecDeque<Result<String, TransportError>>,
    }

    impl Fake {
        fn new(replies: &[&str]) -> Fake {
            Fake { sent: Vec::new(), replies: replies.iter().map(|r| Ok(r.to_string())).collect() }
        }
    }

    impl Transport for Fake {
        fn send(&mut self, line: &str) -> Result<(), TransportError> {
            self.sent.push(line.to_string());
            Ok(())
        }
        fn recv(&mut self, _timeout: Duration) -> Result<String, TransportError> {
            self.replies.pop_front().unwrap_or(Err(TransportError::Closed))
        }
        fn diagnostics(&self) -> String {
            "Traceback ...\nSegmentation fault".into()
        }
    }

    const HELLO_OK: &str = r#"{"id":0,"ok":{"protocol":2,"python":"3.11.7","occt":"8.0.1"}}"#;

    #[test]
    fn handshake_then_requests_with_increasing_ids() {
        let fake = Fake::new(&[HELLO_OK, r#"{"id":1,"ok":{"pong":true}}"#]);
        let mut client = Client::connect(fake).unwrap();
        assert_eq!(client.hello.occt, "8.0.1");
        let pong = client.call_value(&Request::Ping {}).unwrap();
        assert_eq!(pong, serde_json::json!({"pong": true}));
        assert_eq!(
            client.transport.sent,
            [r#"{"id":0,"op":"hello","args":{"protocol":2}}"#, r#"{"id":1,"op":"ping","args":{}}"#]
        );
    }

    #[test]
    fn protocol_mismatch_says_how_to_fix() {
        let fake = Fake::new(&[r#"{"id":0,"ok":{"protocol":3,"python":"3.11.7","occt":"8.0.1"}}"#]);
        let err = Client::connect(fake).err().unwrap();
        assert_eq!(err.code(), Some("protocol_mismatch"));
        assert!(err.to_string().contains("scripts/setup"), "{err}");
    }

    #[test]
    fn ocp_missing_is_passed_on() {
        let fake = Fake::new(&[
            r#"{"id":0,"err":{"code":"ocp_missing","message":"No module named 'OCP'; run scripts/setup"}}"#,
        ]);
        let err = Client::connect(fake).err().unwrap();
        assert_eq!(err.code(), Some("ocp_missing"));
    }

    #[test]
    fn death_mid_request_names_the_op_and_keeps_stderr() {
        let fake = Fake::new(&[HELLO_OK]);
        let mut client = Client::connect(fake).unwrap();
        let err = client.call_value(&Request::LoadStep { path: "a.step".into() }).unwrap_err();
        assert!(matches!(&err, SidecarError::Died { op, .. } if op == "load_step"));
        assert_eq!(err.to_string(), "the OCCT sidecar died during 'load_step' (sidecar stderr: Segmentation fault)");
    }

    #[test]
    fn timeout_is_reported_with_the_op() {
        let mut fake = Fake::new(&[HELLO_OK]);
        fake.replies.push_back(Err(TransportError::Timeout));
        let mut client = Client::connect(fake).unwrap();
        let err = client.call_value(&Request::Describe { handle: 1, mesh: false, mesh_tolerance: 0.1 }).unwrap_err();
        assert!(matches!(&err, SidecarError::Timeout { op, .. } if op == "describe"));
    }

    #[test]
    fn a_sidecar_killed_before_the_handshake_is_not_blamed_on_the_install() {
        assert!(killed_from_outside("Traceback...\nended by signal 9 (SIGKILL)"));
        assert!(killed_from_outside("ended by signal 15 (SIGTERM)\n"));
        // A crash of its own (a segfault importing a broken OCP) is the install's.
        assert!(!killed_from_outside("ended by signal 11 (SIGSEGV)"));
        assert!(!killed_from_outside("ModuleNotFoundError: No module named 'OCP'"));
    }

    #[test]
    fn reply_of_the_wrong_shape_is_a_protocol_error() {
        let fake = Fake::new(&[HELLO_OK, r#"{"id":1,"ok":{"solids":"many"}}"#]);
        let mut client = Client::connect(fake).unwrap();
        let err = client.call::<protocol::Loaded>(&Request::LoadStep { path: "a.step".into() }).unwrap_err();
        assert!(matches!(err, SidecarError::BadReply { .. }));
    }
}

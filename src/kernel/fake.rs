//! An in-memory kernel for unit tests: answers each request with the next scripted reply (the `ok` payload, as
//! the sidecar would send it) and records the requests, so a test drives a stage and asserts on what it asked.

use std::collections::VecDeque;

use serde::de::DeserializeOwned;
use serde_json::Value;

use super::protocol::Request;
use super::{Kernel, SidecarError};

#[derive(Default)]
pub struct FakeKernel {
    pub replies: VecDeque<Value>,
    pub requests: Vec<Request>,
}

impl FakeKernel {
    pub fn new(replies: Vec<Value>) -> FakeKernel {
        FakeKernel { replies: replies.into(), requests: Vec::new() }
    }

    /// The ops asked, in order.
    pub fn ops(&self) -> Vec<&'static str> {
        self.requests.iter().map(Request::op).collect()
    }
}

impl Kernel for FakeKernel {
    fn call<R: DeserializeOwned>(&mut self, request: &Request) -> Result<R, SidecarError> {
        self.requests.push(request.clone());
        let reply = self.replies.pop_front().unwrap_or_else(|| panic!("no scripted reply for '{}'", request.op()));
        // A scripted failure of the op: {"error": {"code": .., "message": ..}}.
        if let Some(error) = reply.get("error").filter(|_| reply.as_object().is_some_and(|o| o.len() == 1)) {
            return Err(SidecarError::Op {
                op: request.op().to_string(),
                code: error["code"].as_str().unwrap_or("kernel_failed").to_string(),
                message: error["message"].as_str().unwrap_or_default().to_string(),
            });
        }
        serde_json::from_value(reply).map_err(|e| SidecarError::BadReply {
            op: request.op().to_string(),
            why: format!("scripted reply of the wrong shape ({e})"),
            line: String::new(),
        })
    }
}

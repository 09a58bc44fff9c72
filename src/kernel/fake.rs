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
        serde_json::from_value(reply).map_err(|e| SidecarError::BadReply {
            op: request.op().to_string(),
            why: format!("scripted reply of the wrong shape ({e})"),
            line: String::new(),
        })
    }
}

//! Every refused request answers a 4xx with a JSON body `{"error": …}` naming the problem
//! (and, for a case file, the `key` and `line`); a fault of the server's own (its disk, its
//! database) is a 500 with the same shape, logged, never a crash.

use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde_json::json;

/// An HTTP error answer.
#[derive(Debug)]
pub struct ApiError {
    pub status: StatusCode,
    pub message: String,
    /// For a case-file error: the key and its 1-based line.
    pub key: Option<String>,
    pub line: Option<usize>,
}

impl ApiError {
    pub fn new(status: StatusCode, message: impl Into<String>) -> Self {
        ApiError {
            status,
            message: message.into(),
            key: None,
            line: None,
        }
    }

    pub fn bad_request(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, message)
    }

    pub fn not_found(what: impl Into<String>) -> Self {
        Self::new(StatusCode::NOT_FOUND, what)
    }

    /// A case-file problem at `key` on `line`.
    pub fn case(message: impl Into<String>, key: Option<String>, line: Option<usize>) -> Self {
        ApiError {
            key,
            line,
            ..Self::bad_request(message)
        }
    }

    /// The server's own fault: logged in full, answered without internals.
    pub fn internal(err: impl std::fmt::Display) -> Self {
        log::error!("service: {err}");
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "internal error (see the server log)",
        )
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let mut body = json!({ "error": self.message });
        if let Some(key) = self.key {
            body["key"] = json!(key);
        }
        if let Some(line) = self.line {
            body["line"] = json!(line);
        }
        (self.status, Json(body)).into_response()
    }
}

impl From<rusqlite::Error> for ApiError {
    fn from(e: rusqlite::Error) -> Self {
        Self::internal(format!("database: {e}"))
    }
}

impl From<std::io::Error> for ApiError {
    fn from(e: std::io::Error) -> Self {
        Self::internal(format!("disk: {e}"))
    }
}

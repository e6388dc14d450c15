//! Who is asking. With `--token-file`, every API call carries `Authorization: Bearer TOKEN`
//! and sees only the jobs made with the same token (the owner is the token's name in the
//! file); without it the service trusts the machine instead, answering loopback connections
//! only. Both checks run before any body is read; `owned` is the one way a handler reaches a
//! job, so another owner's job is as absent as a missing one.

use super::error::ApiError;
use super::files::valid_id;
use super::job::Job;
use super::Shared;
use axum::http::{header, HeaderMap, StatusCode};
use std::net::SocketAddr;
use std::path::Path;

/// The owner of the requests without a token file.
pub const LOCAL_OWNER: &str = "local";

/// The refusal of a remote peer without a token file.
pub const LOOPBACK_ONLY: &str =
    "this server accepts loopback connections only (start it with --token-file to serve others)";

/// How requests are let in.
#[derive(Clone, Debug)]
pub enum Access {
    /// No token file: loopback peers only, all as [`LOCAL_OWNER`].
    Loopback,
    /// `(name, token)` pairs from the token file.
    Tokens(Vec<(String, String)>),
}

/// Read a token file: one `NAME TOKEN` pair a line; blank lines and `#` comments skipped.
pub fn load_tokens(path: &Path) -> anyhow::Result<Access> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| anyhow::anyhow!("{}: cannot read the token file: {e}", path.display()))?;
    let mut tokens: Vec<(String, String)> = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let [name, token] = fields[..] else {
            anyhow::bail!(
                "{}:{}: expected `NAME TOKEN`, got {} fields",
                path.display(),
                k + 1,
                fields.len()
            );
        };
        anyhow::ensure!(
            token.len() >= 16,
            "{}:{}: the token of '{name}' is shorter than 16 characters",
            path.display(),
            k + 1
        );
        anyhow::ensure!(
            !tokens.iter().any(|(n, t)| n == name || t == token),
            "{}:{}: '{name}' or its token is listed twice",
            path.display(),
            k + 1
        );
        tokens.push((name.to_string(), token.to_string()));
    }
    anyhow::ensure!(!tokens.is_empty(), "{}: no tokens", path.display());
    Ok(Access::Tokens(tokens))
}

/// Equal strings, compared in time independent of where they differ.
fn same(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

/// The owner of a request, or the 401/403 that refuses it.
pub fn owner(access: &Access, headers: &HeaderMap, peer: SocketAddr) -> Result<String, ApiError> {
    match access {
        Access::Loopback if peer.ip().is_loopback() => Ok(LOCAL_OWNER.to_string()),
        Access::Loopback => Err(ApiError::new(StatusCode::FORBIDDEN, LOOPBACK_ONLY)),
        Access::Tokens(tokens) => {
            let given = headers
                .get(header::AUTHORIZATION)
                .and_then(|v| v.to_str().ok())
                .and_then(|v| v.strip_prefix("Bearer "))
                .map(str::trim)
                .ok_or_else(|| {
                    ApiError::new(
                        StatusCode::UNAUTHORIZED,
                        "missing `Authorization: Bearer TOKEN` header",
                    )
                })?;
            let mut found = None;
            for (name, token) in tokens {
                if same(token, given) {
                    found = Some(name.clone());
                }
            }
            found.ok_or_else(|| ApiError::new(StatusCode::UNAUTHORIZED, "unknown token"))
        }
    }
}

/// The owner of the request, set by the access layer.
#[derive(Clone, Debug)]
pub struct Owner(pub String);

/// The owner's job `id`; another owner's job is "not found", like a missing one.
pub fn owned(shared: &Shared, owner: &Owner, id: &str) -> Result<Job, ApiError> {
    let missing = || {
        ApiError::not_found(format!(
            "no job '{}'",
            id.chars().take(40).collect::<String>()
        ))
    };
    if !valid_id(id) {
        return Err(missing());
    }
    match shared.store.get(id)? {
        Some(job) if job.owner == owner.0 => Ok(job),
        _ => Err(missing()),
    }
}

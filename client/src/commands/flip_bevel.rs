//! `flip-bevel`: asks a session to flip its needle's bevel.

use anyhow::Result;
use needlesim_proto::v1 as pb;

use super::{check_id, out_line};
use crate::rpc::{Conn, Role};

pub(super) async fn flip_bevel(c: &Conn, id: &str) -> Result<()> {
    check_id(id)?;
    let r = pb::control_service_client::ControlServiceClient::new(c.channel.clone())
        .flip_bevel(c.request(pb::FlipBevelRequest { session_id: id.to_owned(), ..Default::default() })?)
        .await
        .map_err(|s| c.status_error(&format!("flipping the bevel of session {id}"), Role::Controller, Some(id), &s))?
        .into_inner();
    out_line(&format!("bevel flip {} requested for session {id}", r.flips_requested))
}

//! One controller at a time: a session's control lease. A Control stream holds it for its whole
//! life; a SetPose client holds it for [`UNARY_LEASE`] after each pose (so a browser that keeps
//! sending poses keeps it, and an idle one lets go). Anyone else is refused until the holder lets
//! go, unless it asks to take over: the holder is then revoked (a revoked stream ends with
//! ABORTED). IO side only: the real-time thread never touches the lease.
//!
//! An *exclusive* holder ([`ControlLease::take_exclusive`]: a training session's instructor while
//! holding control or pausing the exercise) revokes whoever holds the lease and cannot itself be
//! taken over: every other request is refused with [`Busy::Exclusive`] at once, `take_over` or not,
//! until it lets go. The refusal and the take are decided under the lease's one lock, and every
//! pose is written under it ([`StreamLease::write_if_held`], [`ControlLease::with_unary`]), so no
//! other client's pose lands after an exclusive take, and no client checked before it can take
//! the lease after it.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use tokio::sync::{Notify, watch};

/// How long a SetPose client keeps the lease after its last pose.
pub const UNARY_LEASE: Duration = Duration::from_secs(2);
/// How long a request waits for a Control stream that is ending to let go before it is refused
/// (a controller that closes its stream and opens another, or calls SetPose, right away).
pub const HANDOVER_WAIT: Duration = Duration::from_secs(1);

/// Who holds the lease, when a request is refused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Busy {
    /// A Control stream drives the session.
    Stream,
    /// Another SetPose client sent a pose less than [`UNARY_LEASE`] ago.
    Unary,
    /// An exclusive holder ([`ControlLease::take_exclusive`]) has it: no take-over.
    Exclusive,
}

impl std::fmt::Display for Busy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Busy::Stream => write!(f, "another client drives this session through a Control stream"),
            Busy::Unary => write!(f, "another client drove this session through SetPose less than {} s ago", UNARY_LEASE.as_secs_f64()),
            Busy::Exclusive => write!(f, "a training exercise's instructor holds the control lease exclusively (no take-over)"),
        }
    }
}

enum Holder {
    /// A Control stream, or an exclusive holder; `revoke` tells it that it was taken over.
    Stream { id: u64, revoke: watch::Sender<bool>, exclusive: bool },
    /// A SetPose client (its `client_id`, or its address), until `until`.
    Unary { client: String, until: Instant },
}

#[derive(Default)]
struct Inner {
    next_id: u64,
    holder: Option<Holder>,
}

/// The control lease of one session.
#[derive(Default)]
pub struct ControlLease {
    inner: Mutex<Inner>,
    /// Signalled when a stream lets go.
    released: Notify,
}

impl ControlLease {
    pub fn new() -> Arc<Self> {
        Arc::new(Self::default())
    }

    /// Takes the lease for a Control stream of `client` (its address): granted when nobody holds
    /// it, when a SetPose lease has lapsed or is `client`'s own, or on `take_over` (which revokes
    /// the holder). Waits up to [`HANDOVER_WAIT`] for a stream that is ending.
    pub async fn acquire_stream(self: &Arc<Self>, client: &str, take_over: bool) -> Result<StreamLease, Busy> {
        let deadline = tokio::time::Instant::now() + HANDOVER_WAIT;
        loop {
            let released = self.released.notified();
            tokio::pin!(released);
            released.as_mut().enable();
            match self.try_stream(client, take_over, Instant::now()) {
                Err(Busy::Stream) => {
                    if tokio::time::timeout_at(deadline, released).await.is_err() {
                        return Err(Busy::Stream);
                    }
                }
                other => return other,
            }
        }
    }

    fn try_stream(self: &Arc<Self>, client: &str, take_over: bool, now: Instant) -> Result<StreamLease, Busy> {
        let mut g = self.inner.lock().expect("control lease lock");
        match &g.holder {
            Some(Holder::Stream { exclusive: true, .. }) => return Err(Busy::Exclusive),
            _ if take_over => {}
            Some(Holder::Stream { .. }) => return Err(Busy::Stream),
            Some(Holder::Unary { client: c, until }) if *until > now && c != client => return Err(Busy::Unary),
            _ => {}
        }
        Ok(self.hold_stream(&mut g, false))
    }

    /// Revokes the holder, if any, and makes a new stream lease the holder.
    fn hold_stream(self: &Arc<Self>, g: &mut Inner, exclusive: bool) -> StreamLease {
        revoke(g.holder.take());
        g.next_id += 1;
        let id = g.next_id;
        let (tx, rx) = watch::channel(false);
        g.holder = Some(Holder::Stream { id, revoke: tx, exclusive });
        StreamLease { lease: self.clone(), id, revoked: rx }
    }

    /// Takes the lease exclusively, at once (module docs): whoever holds it is revoked (an
    /// exclusive holder too), and until the returned lease is dropped every other request is
    /// refused with [`Busy::Exclusive`], `take_over` or not.
    pub fn take_exclusive(self: &Arc<Self>) -> StreamLease {
        let mut g = self.inner.lock().expect("control lease lock");
        self.hold_stream(&mut g, true)
    }

    /// SetPose of `client`: runs `write` under the lease, which `client` then holds for
    /// [`UNARY_LEASE`]. Refused while a stream or another SetPose client holds it, unless
    /// `take_over`. Waits up to [`HANDOVER_WAIT`] for a stream that is ending.
    pub async fn with_unary<R>(&self, client: &str, take_over: bool, write: impl FnOnce() -> R) -> Result<R, Busy> {
        let deadline = tokio::time::Instant::now() + HANDOVER_WAIT;
        loop {
            let released = self.released.notified();
            tokio::pin!(released);
            released.as_mut().enable();
            {
                let mut g = self.inner.lock().expect("control lease lock");
                let now = Instant::now();
                let busy = match &g.holder {
                    Some(Holder::Stream { exclusive: true, .. }) => return Err(Busy::Exclusive),
                    _ if take_over => None,
                    Some(Holder::Stream { .. }) => Some(Busy::Stream),
                    Some(Holder::Unary { client: c, until }) if *until > now && c != client => Some(Busy::Unary),
                    _ => None,
                };
                match busy {
                    None => {
                        revoke(g.holder.take());
                        g.holder = Some(Holder::Unary { client: client.to_owned(), until: now + UNARY_LEASE });
                        return Ok(write());
                    }
                    Some(busy @ (Busy::Unary | Busy::Exclusive)) => return Err(busy),
                    Some(Busy::Stream) => {}
                }
            }
            if tokio::time::timeout_at(deadline, released).await.is_err() {
                return Err(Busy::Stream);
            }
        }
    }

    /// Whether a Control stream holds the lease now.
    pub fn stream_holds(&self) -> bool {
        matches!(self.inner.lock().expect("control lease lock").holder, Some(Holder::Stream { .. }))
    }
}

/// Tells a revoked stream holder that it lost the lease.
fn revoke(old: Option<Holder>) {
    if let Some(Holder::Stream { revoke, .. }) = old {
        let _ = revoke.send(true);
    }
}

/// The lease of one Control stream, released when dropped.
pub struct StreamLease {
    lease: Arc<ControlLease>,
    id: u64,
    revoked: watch::Receiver<bool>,
}

impl StreamLease {
    /// Runs `write` if this stream still holds the lease (under the lease, so that no pose of a
    /// revoked stream lands after its successor's); false once it was taken over.
    pub fn write_if_held(&self, write: impl FnOnce()) -> bool {
        let g = self.lease.inner.lock().expect("control lease lock");
        match &g.holder {
            Some(Holder::Stream { id, .. }) if *id == self.id => {
                write();
                true
            }
            _ => false,
        }
    }

    /// Whether this lease still holds (nobody took over).
    pub fn is_held(&self) -> bool {
        let g = self.lease.inner.lock().expect("control lease lock");
        matches!(&g.holder, Some(Holder::Stream { id, .. }) if *id == self.id)
    }

    /// Resolves when another client took over.
    pub async fn revoked(&mut self) {
        // An error means the sender is gone: the holder was replaced, i.e. revoked as well.
        let _ = self.revoked.wait_for(|r| *r).await;
    }
}

impl Drop for StreamLease {
    fn drop(&mut self) {
        let mut g = self.lease.inner.lock().expect("control lease lock");
        if matches!(&g.holder, Some(Holder::Stream { id, .. }) if *id == self.id) {
            g.holder = None;
            drop(g);
            self.lease.released.notify_waiters();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test]
    async fn one_stream_at_a_time_and_take_over() {
        let lease = ControlLease::new();
        let mut first = lease.acquire_stream("a", false).await.unwrap();
        assert!(lease.stream_holds());
        assert_eq!(lease.acquire_stream("a", false).await.err(), Some(Busy::Stream));
        assert_eq!(lease.with_unary("a", false, || ()).await.err(), Some(Busy::Stream));
        let second = lease.acquire_stream("b", true).await.unwrap();
        first.revoked().await;
        assert!(!first.write_if_held(|| panic!("a revoked stream writes")));
        let mut wrote = false;
        assert!(second.write_if_held(|| wrote = true));
        assert!(wrote);
        // The revoked lease's drop does not release its successor's.
        drop(first);
        assert!(lease.stream_holds());
        drop(second);
        assert!(!lease.stream_holds());
        // SetPose: the same client keeps it; another waits for the lease to lapse or takes over.
        assert_eq!(lease.with_unary("web", false, || 1).await, Ok(1));
        assert_eq!(lease.with_unary("web", false, || 2).await, Ok(2));
        assert_eq!(lease.with_unary("cli", false, || 3).await, Err(Busy::Unary));
        assert_eq!(lease.acquire_stream("cli", false).await.err(), Some(Busy::Unary));
        assert!(lease.acquire_stream("web", false).await.is_ok(), "a SetPose client may open a stream");
        assert_eq!(lease.with_unary("cli", true, || 4).await, Ok(4));
    }

    /// Issue 20: an exclusive holder (a training instructor) revokes the holder and is not
    /// revoked by a take-over; whoever acquires after it is refused until it lets go.
    #[tokio::test]
    async fn an_exclusive_holder_cannot_be_taken_over() {
        let lease = ControlLease::new();
        let mut trainee = lease.acquire_stream("trainee", false).await.unwrap();
        let instructor = lease.take_exclusive();
        trainee.revoked().await;
        assert!(!trainee.write_if_held(|| panic!("a revoked stream writes")));
        // A client that was let through before the take cannot take the lease after it.
        assert_eq!(lease.acquire_stream("trainee", true).await.err(), Some(Busy::Exclusive));
        assert_eq!(lease.acquire_stream("trainee", false).await.err(), Some(Busy::Exclusive));
        assert_eq!(lease.with_unary("trainee", true, || panic!("a refused SetPose writes")).await, Err::<(), _>(Busy::Exclusive));
        let mut wrote = false;
        assert!(instructor.write_if_held(|| wrote = true));
        assert!(wrote, "the exclusive holder still writes");
        // A second exclusive take replaces the first (the instructor taking control again).
        let again = lease.take_exclusive();
        assert!(!instructor.write_if_held(|| ()));
        drop(instructor);
        assert_eq!(lease.acquire_stream("trainee", true).await.err(), Some(Busy::Exclusive), "the old lease's drop releases nothing");
        drop(again);
        drop(trainee);
        assert!(lease.acquire_stream("trainee", false).await.is_ok(), "free again once the exclusive holder lets go");
    }

    #[tokio::test]
    async fn a_stream_that_ends_is_waited_for() {
        let lease = ControlLease::new();
        let first = lease.acquire_stream("a", false).await.unwrap();
        let l2 = lease.clone();
        let waiter = tokio::spawn(async move { l2.acquire_stream("a", false).await.is_ok() });
        tokio::time::sleep(HANDOVER_WAIT / 2).await;
        drop(first);
        assert!(waiter.await.unwrap(), "the next stream gets the lease once the first lets go");
    }
}

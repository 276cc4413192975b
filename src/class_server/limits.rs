//! The class server's limits: a token bucket per connection (messages a second, with a burst),
//! the "at most once a second" of the error a flood gets, and the failed join attempts per
//! address that keep join codes and tokens from being guessed by trying.

use std::collections::{HashMap, VecDeque};
use std::net::IpAddr;
use std::time::{Duration, Instant};

/// A student's (and a connection's before it joins) steady rate, messages a second.
pub const STUDENT_RATE: f64 = 10.0;
/// A student's burst: messages taken at once after a quiet while.
pub const STUDENT_BURST: f64 = 20.0;
/// The teacher's steady rate, messages a second (a 30 Hz state stream passes with room).
pub const TEACHER_RATE: f64 = 100.0;
/// The teacher's burst.
pub const TEACHER_BURST: f64 = 200.0;
/// Failed join attempts an address may make in [`ATTEMPT_WINDOW`] before every join from it
/// is refused until the window has passed.
pub const MAX_FAILED_ATTEMPTS: usize = 10;
/// The window of [`MAX_FAILED_ATTEMPTS`].
pub const ATTEMPT_WINDOW: Duration = Duration::from_secs(60);
/// The most addresses remembered at once (older ones are forgotten first).
const MAX_ADDRESSES: usize = 4096;

/// A token bucket: `rate` tokens a second up to `burst`; each message takes one.
#[derive(Debug, Clone)]
pub(crate) struct TokenBucket {
    /// Tokens added a second.
    rate: f64,
    /// The most tokens held.
    burst: f64,
    /// Tokens held now.
    tokens: f64,
    /// When `tokens` was last brought up to date.
    last: Instant,
}

impl TokenBucket {
    /// A full bucket.
    pub(crate) fn new(rate: f64, burst: f64, now: Instant) -> Self {
        Self {
            rate,
            burst,
            tokens: burst,
            last: now,
        }
    }

    /// The same bucket with another rate and burst (a connection that joined as teacher),
    /// full.
    pub(crate) fn reset(&mut self, rate: f64, burst: f64, now: Instant) {
        *self = Self::new(rate, burst, now);
    }

    /// Takes a token if there is one: whether the message may pass.
    pub(crate) fn take(&mut self, now: Instant) -> bool {
        let dt = now.saturating_duration_since(self.last).as_secs_f64();
        self.tokens = (self.tokens + dt * self.rate).min(self.burst);
        self.last = now;
        if self.tokens >= 1.0 {
            self.tokens -= 1.0;
            true
        } else {
            false
        }
    }
}

/// At most one event a `period`: the error a dropped message gets, so that a flood is not
/// answered by a flood.
#[derive(Debug, Clone)]
pub(crate) struct Throttle {
    /// The least time between two events.
    period: Duration,
    /// The last event let through.
    last: Option<Instant>,
}

impl Throttle {
    /// At most one event a `period`.
    pub(crate) fn new(period: Duration) -> Self {
        Self { period, last: None }
    }

    /// Whether an event may happen now (and, if so, that it did).
    pub(crate) fn allow(&mut self, now: Instant) -> bool {
        match self.last {
            Some(t) if now.saturating_duration_since(t) < self.period => false,
            _ => {
                self.last = Some(now);
                true
            }
        }
    }
}

/// The failed join attempts of each address in the last [`ATTEMPT_WINDOW`].
#[derive(Debug, Default)]
pub(crate) struct JoinAttempts {
    /// Each address's failures, oldest first.
    failures: HashMap<IpAddr, VecDeque<Instant>>,
}

impl JoinAttempts {
    /// Whether `ip` has failed [`MAX_FAILED_ATTEMPTS`] times in the window ending `now`.
    pub(crate) fn blocked(&mut self, ip: IpAddr, now: Instant) -> bool {
        let Some(times) = self.failures.get_mut(&ip) else {
            return false;
        };
        forget_old(times, now);
        if times.is_empty() {
            self.failures.remove(&ip);
            return false;
        }
        times.len() >= MAX_FAILED_ATTEMPTS
    }

    /// Counts a failed attempt of `ip` at `now`.
    pub(crate) fn failed(&mut self, ip: IpAddr, now: Instant) {
        if self.failures.len() >= MAX_ADDRESSES && !self.failures.contains_key(&ip) {
            self.failures.retain(|_, times| {
                forget_old(times, now);
                !times.is_empty()
            });
        }
        if self.failures.len() >= MAX_ADDRESSES && !self.failures.contains_key(&ip) {
            // Still full of recent failures: forget the address whose last failure is oldest.
            let oldest = self
                .failures
                .iter()
                .min_by_key(|(_, t)| t.back().copied())
                .map(|(ip, _)| *ip);
            if let Some(old) = oldest {
                self.failures.remove(&old);
            }
        }
        let times = self.failures.entry(ip).or_default();
        forget_old(times, now);
        times.push_back(now);
        while times.len() > MAX_FAILED_ATTEMPTS {
            times.pop_front();
        }
    }
}

/// Drops the failures older than the window.
fn forget_old(times: &mut VecDeque<Instant>, now: Instant) {
    while times
        .front()
        .is_some_and(|t| now.saturating_duration_since(*t) >= ATTEMPT_WINDOW)
    {
        times.pop_front();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bucket_passes_its_burst_then_its_rate() {
        let t0 = Instant::now();
        let mut b = TokenBucket::new(10.0, 20.0, t0);
        let passed = (0..100).filter(|_| b.take(t0)).count();
        assert_eq!(passed, 20);
        // Half a second later: 5 more tokens.
        let t1 = t0 + Duration::from_millis(500);
        let passed = (0..100).filter(|_| b.take(t1)).count();
        assert_eq!(passed, 5);
    }

    #[test]
    fn the_throttle_lets_one_event_a_period_through() {
        let t0 = Instant::now();
        let mut t = Throttle::new(Duration::from_secs(1));
        assert!(t.allow(t0));
        assert!(!t.allow(t0 + Duration::from_millis(999)));
        assert!(t.allow(t0 + Duration::from_millis(1000)));
    }

    #[test]
    fn an_address_is_blocked_after_its_failures_until_the_window_passes() {
        let t0 = Instant::now();
        let ip: IpAddr = [10, 0, 0, 7].into();
        let other: IpAddr = [10, 0, 0, 8].into();
        let mut a = JoinAttempts::default();
        for k in 0..MAX_FAILED_ATTEMPTS {
            assert!(!a.blocked(ip, t0), "blocked after {k} failures");
            a.failed(ip, t0);
        }
        assert!(a.blocked(ip, t0 + Duration::from_secs(59)));
        assert!(!a.blocked(other, t0));
        assert!(!a.blocked(ip, t0 + ATTEMPT_WINDOW));
    }
}

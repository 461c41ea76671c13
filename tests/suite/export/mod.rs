//! The exporters (src/export) against the real peers.

mod peers;

//! Comparison of ryade against YADE's golden records.

pub mod meso;
pub mod micro;

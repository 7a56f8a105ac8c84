//! Comparison of ryade against YADE's golden records.

pub mod micro;

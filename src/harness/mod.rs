//! Comparison of ryade against YADE's golden records.

pub mod assets;
pub mod env;
pub mod meso;
pub mod micro;
pub mod proc;
pub mod study;
pub mod study_run;

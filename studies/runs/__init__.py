"""The study runners of `delvjax reproduce`, one module per figure set (`run(ctx)`), and the
helpers they share (private modules)."""

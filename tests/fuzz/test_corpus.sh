#!/usr/bin/env bash
# Replays the committed fuzz corpus through the fuzz target built with
# ASan+UBSan (a regression test: every input must run clean).
cd "$(dirname "$0")/../.."
exec "${BUILD:-build}/san/test/fuzz/fuzz_replay" tests/fuzz/corpus/*

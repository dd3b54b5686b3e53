// The playback harness.

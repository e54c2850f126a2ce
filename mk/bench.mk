# Benchmarks (make bench). Each binary in $(BUILD)/bench/bin is run by
# tools/bench/run with a JSON output path; see tools/bench/.

# The synthetic 2,000-SV model shared by the onboard benchmarks, written in
# the exported-header format by the trainer's exporter.
SYNTH_GEN := $(BUILD)/bench/tools/make_synthetic_model
SYNTH_HEADER := $(BUILD)/gen/bench/synthetic_ground.h

$(SYNTH_GEN): tools/bench/make_synthetic_model.cpp $(TRAINER_LIB) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(LDFLAGS) $(EIGEN_CFLAGS) -I. $(ONBOARD_INC) $< $(TRAINER_LIB) $(ONBOARD_LIB) -lm -o $@

$(SYNTH_HEADER): $(SYNTH_GEN)
	@mkdir -p $(@D)
	$(SYNTH_GEN) $@

# SVR evaluations per second: hylo (single and batch) against svm_predict, on
# the synthetic model and every committed one (the node's model registry).
BENCH_SVR := $(BUILD)/bench/bin/bench_svr

$(BENCH_SVR): tools/bench/bench_svr.c $(ONBOARD_LIB) $(SYNTH_HEADER) $(BUILD)/obj/node/registry_models.o
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) -D_POSIX_C_SOURCE=199309L $(ONBOARD_INC) -I$(BUILD)/gen $< \
		$(BUILD)/obj/node/registry_models.o $(ONBOARD_LIB) $(SVM_LIBS) -lm -o $@

BENCH_TARGETS += $(BENCH_SVR)

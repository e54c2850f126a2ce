# The model export path end to end (tests/export/): libsvm trains a small
# model, trainer/svr_export.cpp writes its header, and a C99 test compiled
# against that header compares the onboard evaluator with libsvm. A second
# export must give the same bytes.
EXPORT_DIR := $(BUILD)/gen/test-models
EXPORT_GEN := $(BUILD)/test/export/make_test_model
EXPORT_HEADER := $(EXPORT_DIR)/testbot_ground.h
EXPORT_TEST := $(BUILD)/test/export/test_export
EXPORT_TEST_SAN := $(BUILD)/san/test/export/test_export

# These programs link the trainer's own objects (its archive) rather than
# compiling its sources again.
$(EXPORT_GEN): tests/export/make_test_model.cpp $(TRAINER_LIB) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(LDFLAGS) -I. $(ONBOARD_INC) $(EIGEN_CFLAGS) $< $(TRAINER_LIB) $(ONBOARD_LIB) $(SVM_LIBS) -lpthread -lm -o $@

$(EXPORT_HEADER): $(EXPORT_GEN)
	@mkdir -p $(@D)
	$(EXPORT_GEN) $(EXPORT_DIR)

$(EXPORT_TEST): tests/export/test_export.c $(EXPORT_HEADER) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) $(ONBOARD_INC) -I$(EXPORT_DIR) -DREFERENCE_TXT='"$(EXPORT_DIR)/reference.txt"' $< $(ONBOARD_LIB) $(CMOCKA_LIBS) -lm -o $@

$(EXPORT_TEST_SAN): tests/export/test_export.c $(EXPORT_HEADER) $(ONBOARD_LIB_SAN)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) $(SAN_FLAGS) $(ONBOARD_INC) -I$(EXPORT_DIR) -DREFERENCE_TXT='"$(EXPORT_DIR)/reference.txt"' $< $(ONBOARD_LIB_SAN) $(CMOCKA_LIBS) -lm -o $@

ALL_TARGETS += $(EXPORT_TEST) $(EXPORT_TEST_SAN)
TESTS += $(EXPORT_TEST) tests/export/test_export_bytes.sh tests/export/test_models.sh
tests/export/test_models.sh: $(TRAINER) $(ONBOARD_LIB)
TESTS_SAN += $(EXPORT_TEST_SAN)

# The model fit (trainer/svr_fit.cpp) on synthetic data (tests/export/test_fit.cpp).
FIT_TEST := $(BUILD)/test/export/test_fit
$(FIT_TEST): tests/export/test_fit.cpp $(TRAINER_LIB) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(LDFLAGS) -I. $(ONBOARD_INC) $< $(TRAINER_LIB) $(ONBOARD_LIB) $(SVM_LIBS) -lpthread -lm -o $@
ALL_TARGETS += $(FIT_TEST)
TESTS += $(FIT_TEST)

# The envelope's margin widened after a failed fresh check
# (tests/export/test_envelope_widening.cpp), on a model with narrow dips.
WIDENING_TEST := $(BUILD)/test/export/test_envelope_widening
$(WIDENING_TEST): tests/export/test_envelope_widening.cpp $(TRAINER_LIB) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(LDFLAGS) -I. $(ONBOARD_INC) $< $(TRAINER_LIB) $(ONBOARD_LIB) -lpthread -lm -o $@
ALL_TARGETS += $(WIDENING_TEST)
TESTS += $(WIDENING_TEST)

# Headers read back (tests/export/test_header_parse.cpp): the export stage
# reads the fit stage's header before it adds the envelope.
HEADER_PARSE_TEST := $(BUILD)/test/export/test_header_parse
$(HEADER_PARSE_TEST): tests/export/test_header_parse.cpp $(TRAINER_LIB) $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CXX) $(CXX17_FLAGS) $(LDFLAGS) -I. $(ONBOARD_INC) $< $(TRAINER_LIB) $(ONBOARD_LIB) -lm -o $@
ALL_TARGETS += $(HEADER_PARSE_TEST)
TESTS += $(HEADER_PARSE_TEST)

# The committed models' envelopes against their own predictions
# (tests/export/test_envelope_models.c), through the node's model registry.
ENVELOPE_MODELS_TEST := $(BUILD)/test/export/test_envelope_models
$(ENVELOPE_MODELS_TEST): tests/export/test_envelope_models.c tools/cost/random_edge.h $(BUILD)/obj/node/registry_models.o $(ONBOARD_LIB)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) -I. $(ONBOARD_INC) $< $(BUILD)/obj/node/registry_models.o $(ONBOARD_LIB) $(CMOCKA_LIBS) -lm -o $@
ALL_TARGETS += $(ENVELOPE_MODELS_TEST)
TESTS += $(ENVELOPE_MODELS_TEST)

# Documentation checks (tests/docs/test_docs.sh): links and citations stay
# inside the repository (tools/check-docs), committed pictures and results
# are as new as the models and scenes they were made from
# (tools/provenance, docs/provenance.json), the README's tour runs and the
# tiny program it links builds.
tests/docs/test_docs.sh: $(ONBOARD_LIB) $(HYLO_SCENE) $(HYLO_PLANNER) $(HYLO_LISTEN) $(HYLO_RENDER) $(TRAINER) $(HYLO_COST)
TESTS += tests/docs/test_docs.sh

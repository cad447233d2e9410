"""Import of JSBSim flight-dynamics models into certkit aircraft files (:mod:`.importer`)."""

"""The command line (:mod:`certkit.cli.main`) and its printers for ``certkit derivatives`` (:mod:`.aero_report`) and
``certkit trim``/``modes`` (:mod:`.flight_report`). The top layer: nothing below imports it."""

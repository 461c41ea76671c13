"""A Jupyter kernel manager whose client waits for messages one second at a time.

nbclient sends on the shell socket (an Output widget's state) while it awaits the
reply on it, and zmq.asyncio then sometimes misses the reply's wake-up: both sides
sat idle until the cell's timeout, on the widget's cell, in about one run of the
course in three (ipykernel 6 and 7, pyzmq 26 and 27), more often on a busy machine.
Each new wait looks at the socket itself, so a reply that came in unannounced is
read within a second.

Used by tools/export_notebooks.py and python/tests/test_notebooks.py:
    nbclient.NotebookClient(nb, kernel_manager_class=PatientKernelManager, ...)
"""
import time
from queue import Empty

from jupyter_client.asynchronous import AsyncKernelClient
from jupyter_client.channels import AsyncZMQSocketChannel
from jupyter_client.manager import AsyncKernelManager
from traitlets import Type, default


class PatientChannel(AsyncZMQSocketChannel):
    """Waits for a message one second at a time, up to the caller's timeout."""

    async def get_msg(self, timeout=None):
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            try:
                return await super().get_msg(timeout=1.0 if left is None else min(1.0, left))
            except Empty:
                if left is not None and left <= 1.0:
                    raise


class PatientClient(AsyncKernelClient):
    shell_channel_class = Type(PatientChannel)
    iopub_channel_class = Type(PatientChannel)
    control_channel_class = Type(PatientChannel)


class PatientKernelManager(AsyncKernelManager):
    @default("client_factory")
    def _patient_client(self):
        return PatientClient

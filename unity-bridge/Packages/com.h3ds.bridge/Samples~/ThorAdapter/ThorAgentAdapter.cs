// Copy into the AI2-THOR Unity project's Assets (it must compile in Assembly-CSharp, where AI2-THOR's
// scripts are). Runs an action dict through AgentManager.ProcessControlCommand, the entry point
// AI2-THOR's own Python servers use, and waits until the agent reports the action complete.
using System.Collections;
using System.Collections.Generic;
using H3ds.Bridge;
using UnityEngine;

public class ThorAgentAdapter : MonoBehaviour, IThorAgent
{
    [SerializeField] AgentManager agentManager;

    public IEnumerator Run(Dictionary<string, object> action, ThorResult result)
    {
        if (agentManager == null) agentManager = FindObjectOfType<AgentManager>();
        var agent = agentManager.PrimaryAgent;
        agentManager.ProcessControlCommand(new DynamicServerAction(action));
        yield return new WaitUntil(() => agent.agentState == AgentState.ActionComplete || agent.agentState == AgentState.Error);
        result.Success = agent.lastActionSuccess;
        result.Error = agent.errorMessage;
        result.Done = true;
    }

    public IEnumerable<SpawnedObject> SpawnedObjects()
    {
        foreach (var sim in FindObjectsOfType<SimObjPhysics>())
            yield return new SpawnedObject { ObjectId = sim.ObjectID, ObjectType = sim.Type.ToString(), GameObject = sim.gameObject };
    }
}
